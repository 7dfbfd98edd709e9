// The cubic spline kernel of docs/SPH.md eq. (1) (Monaghan 1992), support h: W = 0 for r >= h.
// Needs sph (SphParams) in scope for h.

const float kPi = 3.14159265358979;

// Both functions are written without branches on q: t = max(1 - q, 0) zeroes them past the support,
// and 1/h, uniform across a pass, is hoisted out of the neighbour loops (a walk's cost is its
// per-pair instructions: docs/PERFORMANCE.md "The neighbour walk's per-pair cost").

// W(r), r = |x_i - x_j|.
float kernel_w(float r, float h) {
    float inv_h = 1.0 / h;
    float q = r * inv_h;
    float t = max(1.0 - q, 0.0);
    float shape = q <= 0.5 ? 6.0 * q * q * (q - 1.0) + 1.0 : 2.0 * t * t * t;
    return (8.0 / kPi) * inv_h * inv_h * inv_h * shape;
}

// grad W at d = x_i - x_j, r = |d| > 0:  l*q*(3q - 2)*d/(r h) for q <= 1/2, -l*(1 - q)^2*d/(r h) else,
// l = 48/(pi h^3). Zero at r = 0 (the limit from every side), so the self term drops out.
vec3 kernel_grad(vec3 d, float r, float h) {
    float inv_h = 1.0 / h;
    float q = r * inv_h;
    float t = max(1.0 - q, 0.0);
    float f = q <= 0.5 ? q * (3.0 * q - 2.0) : -t * t;
    float l = (48.0 / kPi) * inv_h * inv_h * inv_h * inv_h;
    return r > 1e-9 * h ? (l * f / r) * d : vec3(0.0);
}
