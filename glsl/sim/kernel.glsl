// The cubic spline kernel of docs/SPH.md eq. (1) (Monaghan 1992), support h: W = 0 for r >= h.
// Needs sph (SphParams) in scope for h.

const float kPi = 3.14159265358979;

// W(r), r = |x_i - x_j|.
float kernel_w(float r, float h) {
    float q = r / h;
    float k = 8.0 / (kPi * h * h * h);
    if (q <= 0.5) return k * (6.0 * q * q * (q - 1.0) + 1.0);
    if (q <= 1.0) { float t = 1.0 - q; return k * 2.0 * t * t * t; }
    return 0.0;
}

// grad W at d = x_i - x_j, r = |d| > 0:  l*q*(3q - 2)*d/(r h) for q <= 1/2, -l*(1 - q)^2*d/(r h) else,
// l = 48/(pi h^3). Zero at r = 0 (the limit from every side), so the self term drops out.
vec3 kernel_grad(vec3 d, float r, float h) {
    float q = r / h;
    if (r <= 1e-9 * h || q > 1.0) return vec3(0.0);
    float l = 48.0 / (kPi * h * h * h);
    float f = q <= 0.5 ? q * (3.0 * q - 2.0) : -(1.0 - q) * (1.0 - q);
    return (l * f / (r * h)) * d;
}
