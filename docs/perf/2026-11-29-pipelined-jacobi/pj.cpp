// Experiment: relaxed Jacobi (2 walks an iteration) against a delayed Jacobi whose single walk both
// computes a(kappa_k) and the exact residual of kappa_{k-1}, with and without Chebyshev weights.
#include <cmath>
#include <cstdio>
#include <vector>
#include <algorithm>
#include <functional>
struct V { double x = 0, y = 0, z = 0; };
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double len(V a) { return std::sqrt(dot(a, a)); }
const double PI = 3.14159265358979;
double dx = 0.01, h = 0.02, rho0 = 1000, m = rho0 * dx * dx * dx, sig = 8 / (PI * h * h * h);
double W(double r) { double q = r / h; if (q > 1) return 0; return q <= 0.5 ? sig * (6 * (q * q * q - q * q) + 1) : 2 * sig * std::pow(1 - q, 3); }
V gradW(V r) { double d = len(r); if (d <= 0 || d >= h) return {}; double q = d / h;
  double dw = q <= 0.5 ? sig / h * (18 * q * q - 12 * q) : -6 * sig / h * (1 - q) * (1 - q); return (dw / d) * r; }
struct Pair { int i, j; V g; };
int main(int argc, char** argv) {
  int nx = 10, ny = argc > 1 ? atoi(argv[1]) : 30, nz = 6; double pitch = argc > 2 ? atof(argv[2]) : 0.99, dt = 2e-3;
  std::vector<V> x, b;
  for (int i = 0; i < nx; ++i) for (int j = 0; j < ny; ++j) for (int k = 0; k < nz; ++k)
    x.push_back({(i + 0.5) * dx * pitch, (j + 0.5) * dx * pitch, (k + 0.5) * dx * pitch});
  double X = nx * dx, Y = (ny + 3) * dx, Z = nz * dx;
  for (int i = -2; i < nx + 2; ++i) for (int j = -2; j < ny + 3; ++j) for (int k = -2; k < nz + 2; ++k) {
    bool inside = i >= 0 && i < nx && j >= 0 && k >= 0 && k < nz;
    if (!inside) b.push_back({(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx});
  }
  (void)X; (void)Y; (void)Z;
  int n = x.size(), nb = b.size();
  std::vector<double> psi(nb);
  for (int p = 0; p < nb; ++p) { double s = 0; for (int q = 0; q < nb; ++q) s += W(len(b[p] - b[q])); psi[p] = rho0 / s; }
  std::vector<Pair> ff; std::vector<Pair> fb;
  std::vector<double> rho(n, 0); std::vector<V> A(n), B(n); std::vector<double> sq(n, 0);
  for (int i = 0; i < n; ++i) {
    rho[i] += m * W(0);
    for (int j = 0; j < n; ++j) if (j != i && len(x[i] - x[j]) < h) { V g = gradW(x[i] - x[j]); ff.push_back({i, j, g}); rho[i] += m * W(len(x[i] - x[j])); A[i] = A[i] + m * g; sq[i] += m * m * dot(g, g); }
    for (int p = 0; p < nb; ++p) if (len(x[i] - b[p]) < h) { V g = gradW(x[i] - b[p]); fb.push_back({i, p, g}); rho[i] += psi[p] * W(len(x[i] - b[p])); B[i] = B[i] + psi[p] * g; }
  }
  V vstar{0, -9.81 * dt, 0};
  std::vector<double> src(n), fac(n);
  for (int i = 0; i < n; ++i) { double rate = dot(vstar, B[i]); src[i] = rho0 - (rho[i] + dt * rate); V s = A[i] + B[i]; double d = dot(s, s) + sq[i]; fac[i] = d > 0 ? 1 / d : 0; }
  double meanrho = 0, maxs = 0; for (int i = 0; i < n; ++i) { meanrho += rho[i] / n; maxs = std::max(maxs, -src[i]); }
  auto accel = [&](const std::vector<double>& k) { std::vector<V> a(n);
    for (auto& p : ff) a[p.i] = a[p.i] - (m * (k[p.i] + k[p.j])) * p.g;
    for (auto& p : fb) a[p.i] = a[p.i] - (k[p.i] * psi[p.j]) * p.g; return a; };
  auto resid = [&](const std::vector<V>& a) { std::vector<double> r(n, 0);
    for (auto& p : ff) r[p.i] += m * dot(a[p.i] - a[p.j], p.g);
    for (auto& p : fb) r[p.i] += psi[p.j] * dot(a[p.i], p.g);
    for (int i = 0; i < n; ++i) r[i] = dt * dt * r[i] - src[i]; return r; };
  auto err = [&](const std::vector<double>& r) { double e = 0, pk = 0; for (double v : r) { e += std::min(std::max(v, 0.0) / rho0, 1.0); pk = std::max(pk, std::min(std::max(v, 0.0) / rho0, 1.0)); } return std::make_pair(e / n, pk); };
  double omega = 0.5;
  std::printf("n %d, nb %d, pairs %zu, mean rho %.4f rho0, largest excess %.4f rho0\n", n, nb, ff.size(), meanrho / rho0, maxs / rho0);
  // Standard: kappa_{k+1} = max(kappa_k + omega fac r(kappa_k)/dt^2, 0), Chebyshev from k >= 2; walks = 2/iteration.
  auto standard = [&](double rc, double eta, double etap) {
    std::vector<double> k(n, 0), prev(n, 0); double w = 1;
    for (int it = 0; it < 3000; ++it) {
      auto r = resid(accel(k)); auto [e, pk] = err(r);
      if (e <= eta && pk <= etap && it >= 1) return 2 * it + 2;   // iterations 0..it, an accelerate and a residual pass each
      if (it == 2) w = 2 / (2 - rc * rc); else if (it > 2) w = 4 / (4 - rc * rc * w);
      for (int i = 0; i < n; ++i) { double nx_ = std::max(k[i] + omega * r[i] * fac[i] / (dt * dt), 0.0);
        if (rc > 0 && it >= 2) nx_ = std::max(w * (nx_ - prev[i]) + prev[i], 0.0); prev[i] = k[i]; k[i] = nx_; }
    }
    return -1; };
  // Delayed: one walk a pass computes a(kappa_k) and r(kappa_{k-1}); kappa_{k+1} = max(kappa_k + omega' fac r(kappa_{k-1}), 0).
  auto delayed = [&](double om, double rc, double eta, double etap) {
    std::vector<double> k(n, 0), km1(n, 0); std::vector<V> am1 = accel(k); int walks = 1; double w = 1;
    for (int it = 0; it < 6000; ++it) {
      auto r = resid(am1); auto [e, pk] = err(r); walks++;   // the pass: r(kappa_{k-1}) and a(kappa_k)
      if (e <= eta && pk <= etap && it >= 1) return walks;
      if (it == 2) w = 2 / (2 - rc * rc); else if (it > 2) w = 4 / (4 - rc * rc * w);
      std::vector<double> next(n);
      for (int i = 0; i < n; ++i) { double j = std::max(k[i] + om * r[i] * fac[i] / (dt * dt), 0.0);
        if (rc > 0 && it >= 2) j = std::max(w * (j - km1[i]) + km1[i], 0.0); next[i] = j; }
      am1 = accel(k); km1 = k; k = next;
    }
    return -1; };
  // Mixed lag: one walk computes a_i(kappa_k) and the residual with its own a_i(kappa_k) but the
  // neighbours' a_j(kappa_{k-1}); kappa_{k+1} = max(kappa_k + omega fac r~/dt^2, 0) (Chebyshev as above).
  auto mixed = [&](double om, double rc, double eta, double etap, int& true_walks) {
    std::vector<double> k(n, 0), prev(n, 0); std::vector<V> am1 = accel(k); int walks = 1; double w = 1;
    for (int it = 0; it < 6000; ++it) {
      std::vector<V> a = accel(k); walks++;
      std::vector<double> r(n, 0);
      for (auto& p : ff) r[p.i] += m * dot(a[p.i] - am1[p.j], p.g);
      for (auto& p : fb) r[p.i] += psi[p.j] * dot(a[p.i], p.g);
      for (int i = 0; i < n; ++i) r[i] = dt * dt * r[i] - src[i];
      auto [e, pk] = err(r);
      if (e <= eta && pk <= etap && it >= 1) { auto [te, tp] = err(resid(a)); true_walks = (te <= eta && tp <= etap) ? 1 : 0; return walks; }
      if (it == 2) w = 2 / (2 - rc * rc); else if (it > 2) w = 4 / (4 - rc * rc * w);
      for (int i = 0; i < n; ++i) { double j = std::max(k[i] + om * r[i] * fac[i] / (dt * dt), 0.0);
        if (rc > 0 && it >= 2) j = std::max(w * (j - prev[i]) + prev[i], 0.0); prev[i] = k[i]; k[i] = j; }
      am1 = a;
    }
    return -1; };
  {
    int ok = 0;
    for (double om : {0.25, 0.35, 0.5}) for (double rc : {0.0, 0.9, 0.95, 0.98}) { int wk = mixed(om, rc, 1e-3, 1e-2, ok);
      std::printf("  mixed omega %.2f rho_c %.2f: %d (true residual within the bounds at the stop: %d)\n", om, rc, wk, ok); }
  }
  if (argc > 3) return 0;
  for (double eta : {1e-3, 1e-4}) {
    double etap = eta == 1e-3 ? 1e-2 : 1.0;
    std::printf("eta %g eta_p %g: walks (accelerate + residual passes) to converge\n", eta, etap);
    for (double rc : {0.0, 0.9, 0.95, 0.98}) std::printf("  standard rho_c %.2f: %d\n", rc, standard(rc, eta, etap));
    for (double om : {0.25, 0.35, 0.5}) for (double rc : {0.0, 0.9, 0.95, 0.98}) std::printf("  delayed omega %.2f rho_c %.2f: %d\n", om, rc, delayed(om, rc, eta, etap));
  }
}
