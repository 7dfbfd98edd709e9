// The cubic spline kernel of docs/SPH.md eq. (1) (Monaghan 1992), support h: W = 0 for r >= h.
// The fluid's walks call the forms of glsl/sim/fluid/fluid.glsl, kernel_w(r) and kernel_grad(d, r),
// whose constants (1/h and the two scales) come from SphParams, computed once on the CPU: derived from
// h in the shader, the compiler recomputed them inside every neighbour loop (a walk's cost is its
// per-pair instructions: docs/PERFORMANCE.md "The neighbour walk's per-pair cost",
// "The kernel's constants as operands").

const float kPi = 3.14159265358979;

// Both are written without branches on q: t = max(1 - q, 0) zeroes them past the support.

// W(r), r = |x_i - x_j|, from inv_h = 1/h and w_scale = 8/(pi h^3).
float kernel_w_of(float r, float inv_h, float w_scale) {
    float q = r * inv_h;
    float t = max(1.0 - q, 0.0);
    float shape = q <= 0.5 ? 6.0 * q * q * (q - 1.0) + 1.0 : 2.0 * t * t * t;
    return w_scale * shape;
}

// W(r) at support h (the surface's splats, whose radius is their own).
float kernel_w(float r, float h) {
    float inv_h = 1.0 / h;
    return kernel_w_of(r, inv_h, (8.0 / kPi) * inv_h * inv_h * inv_h);
}

// grad W at d = x_i - x_j, r = |d|: l q (3q - 2) d/(r h) for q <= 1/2, -l (1 - q)^2 d/(r h) else,
// l = 48/(pi h^3); from inv_h and grad_scale = l/h = 48/(pi h^4). For q <= 1/2, q/r = 1/h takes the
// division by r out, so the gradient is zero at r = 0 (d = 0) and the self term drops out without a
// test on r.
vec3 kernel_grad_of(vec3 d, float r, float inv_h, float grad_scale) {
    float q = r * inv_h;
    float t = max(1.0 - q, 0.0);
    float f_over_r = q <= 0.5 ? (3.0 * q - 2.0) * inv_h : -t * t / r;
    return (grad_scale * f_over_r) * d;
}
