// A CPU model (double precision) of DFSPH's step with the boundary rows, on a state the engine wrote (a
// checkpoint), to ask one question: does a two-level solve with a Galerkin coarse level (aggregates of
// particles in cells, unsmoothed or smoothed, A_c = P^T S B P solved exactly) converge a settled pool's
// density solve in fewer walks than the shipped relaxed Jacobi with Chebyshev acceleration ((D10)), and
// does its count stay flat as the step grows? README.md says how to run it and what each switch does.
//
// The model: docs/DFSPH.md (D2)-(D4), (D6), (D9), (D10): fluid particles of mass m, boundary
// particles of Akinci volume psi_b; rows = boundary particles within h of the fluid, each with its own
// kappa_b >= 0. Not modelled: viscosity and the wall's drag (v* = v + dt g), the divergence solve,
// (D8)'s step rule (the step is fixed), the kernel-gradient correction and (D12) (the dam break uses
// neither). The divergence solve (D5) is modelled: plain relaxed Jacobi from w_v times the last impulse. The trajectory is advanced by the shipped scheme; every other scheme is run "in the
// shadow" from the same warm start and the same state at each step, and only its count is recorded.
//
// Unknowns z = (kappa_i fluid, kappa_b rows), weights S = (m, psi_b): B z = -delta_rho(z) (two walks,
// accelerate and density change) is symmetric in the S inner product; the solve is the minimum of
// E(z) = 1/2 z^T S B z + z^T S s over z >= 0 (s = rho0 - rho*; residual r = -Bz - s = excess density).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

struct V { double x = 0, y = 0, z = 0; };
static V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
static V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
static V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
static double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double len(V a) { return std::sqrt(dot(a, a)); }
static const double PI = 3.14159265358979;

static double dx, h, rho0 = 1000, m, sig;
static double W(double r) { double q = r / h; if (q >= 1) return 0; return q <= 0.5 ? sig * (6 * (q * q * q - q * q) + 1) : 2 * sig * std::pow(1 - q, 3); }
static V gradW(V r) { double d = len(r); if (d <= 1e-12 || d >= h) return {}; double q = d / h;
    double dw = q <= 0.5 ? sig / h * (18 * q * q - 12 * q) : -6 * sig / h * (1 - q) * (1 - q); return (dw / d) * r; }

struct Grid {
    double cell; V lo; int nx, ny, nz; std::vector<std::vector<int>> cells;
    void build(const std::vector<V>& p, double c, V lo_, V hi_) {
        cell = c; lo = lo_; nx = int((hi_.x - lo.x) / c) + 1; ny = int((hi_.y - lo.y) / c) + 1; nz = int((hi_.z - lo.z) / c) + 1;
        cells.assign(size_t(nx) * ny * nz, {});
        for (int i = 0; i < int(p.size()); ++i) cells[idx(p[i])].push_back(i);
    }
    int cx(double v, double l, int n) const { return std::clamp(int((v - l) / cell), 0, n - 1); }
    size_t idx(V p) const { return (size_t(cx(p.z, lo.z, nz)) * ny + cx(p.y, lo.y, ny)) * nx + cx(p.x, lo.x, nx); }
    template <class F> void near(V p, F f) const {
        int ix = cx(p.x, lo.x, nx), iy = cx(p.y, lo.y, ny), iz = cx(p.z, lo.z, nz);
        for (int z = std::max(iz - 1, 0); z <= std::min(iz + 1, nz - 1); ++z)
            for (int y = std::max(iy - 1, 0); y <= std::min(iy + 1, ny - 1); ++y)
                for (int x = std::max(ix - 1, 0); x <= std::min(ix + 1, nx - 1); ++x)
                    for (int j : cells[(size_t(z) * ny + y) * nx + x]) f(j);
    }
};

struct Pair { int i, j; V g; };

struct Problem {   // one step's density solve, positions fixed
    int n = 0, R = 0;                  // fluid particles, rows
    std::vector<Pair> ff, fb;          // fluid-fluid (both directions), fluid-row (row index in j)
    std::vector<double> psi_row;       // psi of each row
    std::vector<V> xrow;
    std::vector<double> src;           // s = rho0 - rho* for fluid then rows
    std::vector<double> diag;          // fluid: 1/D_i (D2); rows: 1/D_b (l1, D9)
    std::vector<double> S;             // weights: m, psi_b
    std::vector<int> neighbours;
    std::vector<double> rho, rhob_full, own;   // summation densities (fluid; rows incl. the wall's own part)
    double dt;
    // Density rates (D1) of the fluid and the rows for velocities v.
    void rates(const std::vector<V>& v, std::vector<double>& rf, std::vector<double>& rb) const {
        rf.assign(n, 0.0); rb.assign(R, 0.0);
        for (auto& p : ff) rf[p.i] += m * dot(v[p.i] - v[p.j], p.g);
        for (auto& p : fb) { rf[p.i] += psi_row[p.j] * dot(v[p.i], p.g); rb[p.j] += m * dot(V{} - v[p.i], -1.0 * p.g); }
    }
    // (D4) with v* = v: s = rho0 - rho*, the rows' rest density at least their own part.
    void density_source(const std::vector<V>& v) {
        std::vector<double> rf, rb; rates(v, rf, rb); src.assign(N(), 0.0);
        for (int i = 0; i < n; ++i) src[i] = rho0 - (rho[i] + dt * rf[i]);
        for (int k = 0; k < R; ++k) src[n + k] = std::max(rho0, own[k]) - (rhob_full[k] + dt * rb[k]);
    }
    // (D5): s = -dt Drho/Dt, none where the particle has fewer than 20 neighbours (its row excluded).
    std::vector<char> excluded;
    void divergence_source(const std::vector<V>& v) {
        std::vector<double> rf, rb; rates(v, rf, rb); src.assign(N(), 0.0); excluded.assign(N(), 0);
        for (int i = 0; i < n; ++i) { src[i] = -dt * rf[i]; if (neighbours[i] < 20) { src[i] = 0; excluded[i] = 1; } }
        for (int k = 0; k < R; ++k) src[n + k] = -dt * rb[k];
    }
    int N() const { return n + R; }
    // B z = -delta_rho(z): two walks.
    std::vector<double> apply(const std::vector<double>& z) const {
        std::vector<V> a(n);
        for (auto& p : ff) a[p.i] = a[p.i] - (m * (z[p.i] + z[p.j])) * p.g;
        for (auto& p : fb) a[p.i] = a[p.i] - (psi_row[p.j] * (z[p.i] + z[n + p.j])) * p.g;
        std::vector<double> d(N(), 0.0);
        for (auto& p : ff) d[p.i] += m * dot(a[p.i] - a[p.j], p.g);
        for (auto& p : fb) { d[p.i] += psi_row[p.j] * dot(a[p.i], p.g); d[n + p.j] += m * dot(V{} - a[p.i], -1.0 * p.g); }
        for (auto& v : d) v *= -dt * dt;
        return d;
    }
    std::vector<double> residual(const std::vector<double>& z, const std::vector<double>& Bz) const {
        std::vector<double> r(N()); for (int k = 0; k < N(); ++k) r[k] = -Bz[k] - src[k]; (void)z; return r;
    }
    const std::vector<double>* kappa_for_error = nullptr;   // (D6)'s complementarity error: |r_i| where kappa_i > 0
    std::pair<double, double> error(const std::vector<double>& r) const {
        double e = 0, pk = 0; for (int i = 0; i < n; ++i) { double ri = (kappa_for_error && (*kappa_for_error)[i] > 0) ? std::abs(r[i]) : std::max(r[i], 0.0);
            double v = std::min(ri / rho0, 1.0); e += v; pk = std::max(pk, v); }
        return {e / n, pk};
    }
    double energy(const std::vector<double>& z, const std::vector<double>& Bz) const {
        double e = 0; for (int k = 0; k < N(); ++k) e += S[k] * z[k] * (0.5 * Bz[k] + src[k]); return e;
    }
};

struct State { std::vector<V> x, v; std::vector<double> kappa, kappa_v_impulse; std::vector<double> kappa_b; double dt_prev = 1.0 / 60 / 13; };

static std::vector<V> bx; static std::vector<double> bpsi; static Grid bgrid;
static V glo, ghi; static const V gravity{0, -9.81, 0};

// Builds the step's problem from the state: neighbours, densities, (D2), rows, sources; the warm start
// (w = 1, dropped where a particle separates) into z0.
static Problem build(const State& st, double dt, std::vector<double>& z0, std::vector<int>& row_of_b) {
    Problem P; P.n = int(st.x.size()); P.dt = dt;
    Grid g; g.build(st.x, h, glo, ghi);
    std::vector<double> rho(P.n, 0.0); std::vector<V> A(P.n), Bs(P.n); std::vector<double> sq(P.n, 0.0);
    P.neighbours.assign(P.n, 0);
    row_of_b.assign(bx.size(), -1);
    std::vector<double> rate(P.n, 0.0);
    std::vector<V> vs(P.n); for (int i = 0; i < P.n; ++i) vs[i] = st.v[i] + dt * gravity;
    for (int i = 0; i < P.n; ++i) {
        rho[i] += m * W(0);
        g.near(st.x[i], [&](int j) { if (j == i) return; V d = st.x[i] - st.x[j]; double r = len(d); if (r >= h) return;
            V gw = gradW(d); P.ff.push_back({i, j, gw}); rho[i] += m * W(r); A[i] = A[i] + m * gw; sq[i] += m * m * dot(gw, gw);
            rate[i] += m * dot(vs[i] - vs[j], gw); P.neighbours[i]++; });
        bgrid.near(st.x[i], [&](int b) { V d = st.x[i] - bx[b]; double r = len(d); if (r >= h) return;
            V gw = gradW(d); if (row_of_b[b] < 0) { row_of_b[b] = P.R++; P.psi_row.push_back(bpsi[b]); P.xrow.push_back(bx[b]); }
            P.fb.push_back({i, row_of_b[b], gw}); rho[i] += bpsi[b] * W(r); Bs[i] = Bs[i] + bpsi[b] * gw; sq[i] += bpsi[b] * bpsi[b] * dot(gw, gw) * 0;
            rate[i] += bpsi[b] * dot(vs[i], gw); P.neighbours[i]++; });
    }
    P.src.assign(P.N(), 0.0); P.diag.assign(P.N(), 0.0); P.S.assign(P.N(), m);
    for (int i = 0; i < P.n; ++i) {
        P.src[i] = rho0 - (rho[i] + dt * rate[i]);
        V s = A[i] + Bs[i]; double d = dot(s, s) + sq[i]; P.diag[i] = d > 0 ? 1 / d : 0;
    }
    // rows: density, source, l1 diagonal
    std::vector<double> u(P.n, 0.0);
    { std::vector<double> l1(P.n, 0.0); for (auto& p : P.ff) l1[p.i] += m * len(p.g); for (auto& p : P.fb) l1[p.i] += m * len(p.g);
      for (int i = 0; i < P.n; ++i) u[i] = len(A[i] + Bs[i]) + l1[i]; }
    std::vector<double> rhob(P.R, 0.0), rateb(P.R, 0.0), own(P.R, 0.0), Db(P.R, 0.0);
    for (auto& p : P.fb) { double r = len(st.x[p.i] - P.xrow[p.j]); rhob[p.j] += m * W(r); V gbj = -1.0 * p.g; rateb[p.j] += m * dot(V{} - vs[p.i], gbj); Db[p.j] += len(p.g) * u[p.i]; }
    for (size_t b = 0; b < bx.size(); ++b) if (row_of_b[b] >= 0) { int k = row_of_b[b]; double s = 0;
        bgrid.near(bx[b], [&](int c) { double r = len(bx[b] - bx[c]); if (r < h) s += bpsi[c] * W(r); }); own[k] = s; }
    for (int k = 0; k < P.R; ++k) {
        P.src[P.n + k] = std::max(rho0, own[k]) - (rhob[k] + own[k] + dt * rateb[k]);
        double D = P.psi_row[k] * Db[k]; P.diag[P.n + k] = D > 0 ? 1 / D : 0; P.S[P.n + k] = P.psi_row[k];
    }
    P.rho = rho; P.own = own; P.rhob_full.resize(P.R); for (int k = 0; k < P.R; ++k) P.rhob_full[k] = rhob[k] + own[k];
    z0.assign(P.N(), 0.0);
    for (int i = 0; i < P.n; ++i) {
        double pred = rho0 - P.src[i];
        z0[i] = (pred < 0.99 * rho0 || P.neighbours[i] < 20) ? 0.0 : st.kappa[i];
    }
    for (size_t b = 0; b < bx.size(); ++b) if (row_of_b[b] >= 0) z0[P.n + row_of_b[b]] = st.kappa_b[b];
    return P;
}

static double eta_v = 1e-3, w_v = 0.5, w_dens = 1.0;
static std::vector<V> accel_of(const Problem& P, const std::vector<double>& z) {
    std::vector<V> a(P.n);
    for (auto& p : P.ff) a[p.i] = a[p.i] - (m * (z[p.i] + z[p.j])) * p.g;
    for (auto& p : P.fb) a[p.i] = a[p.i] - (P.psi_row[p.j] * (z[p.i] + z[P.n + p.j])) * p.g;
    return a;
}
// The step up to the density solve: geometry, the divergence solve (D5) from w_v times the last impulse,
// v* = v + dt (a(kappa_v) + g); then the density solve's source and warm start. div_it: its iterations.
static Problem prepare(State& st, double dt, std::vector<double>& z0, std::vector<int>& row_of_b, std::vector<V>& vstar,
                       std::vector<double>& kappa_v, int& div_it) {
    Problem P = build(st, dt, z0, row_of_b);
    P.divergence_source(st.v);
    std::vector<double> z(P.N(), 0.0);
    for (int i = 0; i < P.n; ++i) z[i] = P.excluded[i] ? 0.0 : w_v * st.kappa_v_impulse[i] / dt;
    div_it = 0;
    for (int it = 0; it < 100; ++it) {
        auto Bz = P.apply(z); auto r = P.residual(z, Bz);
        double e = 0; for (int i = 0; i < P.n; ++i) if (!P.excluded[i]) e += std::max(r[i], 0.0) / rho0; e /= P.n;
        if (it >= 1 && e <= eta_v) break;
        div_it = it + 1;
        for (int k = 0; k < P.N(); ++k) { if (k < P.n && P.excluded[k]) continue; double om = k < P.n ? 0.5 : 1.0;
            z[k] = std::max(z[k] + om * r[k] * P.diag[k] / (dt * dt), 0.0); }
    }
    kappa_v = z;
    auto a = accel_of(P, z);
    vstar.resize(P.n); for (int i = 0; i < P.n; ++i) vstar[i] = st.v[i] + dt * (a[i] + gravity);
    P.density_source(vstar);
    for (int i = 0; i < P.n; ++i) { double pred = rho0 - P.src[i]; double k0 = st.kappa[i];
        if (getenv("CWS")) k0 = std::max(st.kappa[i] + st.kappa_v_impulse[i] / st.dt_prev - kappa_v[i], 0.0);   // the last step's whole pressure less what the divergence solve applied now
        z0[i] = (pred < 0.99 * rho0 || P.neighbours[i] < 20) ? 0.0 : w_dens * k0; }
    for (int k = P.n; k < P.N(); ++k) z0[k] *= w_dens;
    return P;
}

struct Stats { int walks = 0, iterations = 0, coarse = 0, rejected = 0; double err = 0, peak = 0; bool converged = false; };
static double omega = 0.5, omega_b = 1.0, rho_c = 0.98, eta = 1e-3, eta_p = 1e-2;
static int min_it = 2, max_it = 100; static bool trace = false;

// One (D6)/(D9) update with (D10)'s weight w (w = 1: plain); prev the iterate before.
static void jacobi(const Problem& P, std::vector<double>& z, std::vector<double>& prev, const std::vector<double>& r, double w) {
    for (int k = 0; k < P.N(); ++k) {
        double om = k < P.n ? omega : omega_b;
        double j = std::max(z[k] + om * r[k] * P.diag[k] / (P.dt * P.dt), 0.0);
        if (w != 1.0) j = std::max(w * (j - prev[k]) + prev[k], 0.0);
        prev[k] = z[k]; z[k] = j;
    }
}

// The shipped solve: (D10) from iteration 2, the rows in the step.
static bool complementarity = false;
static Stats shipped(const Problem& P, std::vector<double>& z) {
    Stats st; std::vector<double> prev = z; double w = 1;
    for (int it = 0; it < max_it; ++it) {
        auto Bz = P.apply(z); st.walks += 2; auto r = P.residual(z, Bz);
        const_cast<Problem&>(P).kappa_for_error = complementarity ? &z : nullptr; auto [e, pk] = P.error(r); const_cast<Problem&>(P).kappa_for_error = nullptr;
        st.err = e; st.peak = pk; st.iterations = it + 1;
        if (trace) std::printf("    S it %d mean %.2e peak %.2e\n", it, e, pk);
        if (it + 1 >= min_it && e <= eta && pk <= eta_p) { st.converged = true; st.iterations = it; break; }
        if (it == 2) w = 2 / (2 - rho_c * rho_c); else if (it > 2) w = 4 / (4 - rho_c * rho_c * w);
        jacobi(P, z, prev, r, it >= 2 ? w : 1.0);
    }
    return st;
}

// Smoothed aggregation (P_s = (I - M B_F) P_F, M the smoother's relaxed diagonal, B_F = T B T on the free
// set F), the coarse problem P_s^T S B_F P_s e = P_s^T S r solved matrix-free by conjugate gradients.
static double omega_p = 1.0;   // scales the prolongation smoother relative to the solve's relaxation
static Stats two_level_sa(const Problem& P, const std::vector<V>& xf, std::vector<double>& z, double H, int nu, bool cheb, int first, bool smooth) {
    Stats st; std::vector<double> prev = z; double w = 1; int since = 0;
    std::vector<double> zsave; double Esave = 0; bool pending = false;
    auto pos = [&](int k) { return k < P.n ? xf[k] : P.xrow[k - P.n]; };
    std::vector<double> M(P.N()); for (int k = 0; k < P.N(); ++k) M[k] = omega_p * (k < P.n ? omega : omega_b) * P.diag[k] / (P.dt * P.dt);
    for (int it = 0; it < max_it; ++it) {
        auto Bz = P.apply(z); st.walks += 2; auto r = P.residual(z, Bz); auto [e, pk] = P.error(r);
        double E = P.energy(z, Bz);
        if (pending) { pending = false; if (E > Esave) { st.rejected++; z = zsave; Bz = P.apply(z); r = P.residual(z, Bz); std::tie(e, pk) = P.error(r); E = Esave; } }
        st.err = e; st.peak = pk; st.iterations = it + 1;
        if (trace) std::printf("    A it %d mean %.2e peak %.2e E %.6e\n", it, e, pk, E);
        if (it + 1 >= min_it && e <= eta && pk <= eta_p) { st.converged = true; st.iterations = it; break; }
        if (it >= first && (it - first) % nu == 0) {
            std::vector<char> F(P.N()); for (int k = 0; k < P.N(); ++k) F[k] = z[k] > 0 || r[k] > 0;
            std::map<std::tuple<int, int, int>, int> ids; std::vector<int> agg(P.N(), -1); int nc = 0;
            for (int k = 0; k < P.N(); ++k) if (F[k]) { V p = pos(k);
                auto key = std::make_tuple(int(std::floor((p.x - glo.x) / H)), int(std::floor((p.y - glo.y) / H)), int(std::floor((p.z - glo.z) / H)));
                auto f = ids.find(key); if (f == ids.end()) f = ids.emplace(key, nc++).first; agg[k] = f->second; }
            auto BF = [&](std::vector<double> y) { for (int k = 0; k < P.N(); ++k) if (!F[k]) y[k] = 0; auto b = P.apply(y); for (int k = 0; k < P.N(); ++k) if (!F[k]) b[k] = 0; return b; };
            auto prolong = [&](const std::vector<double>& ec) { std::vector<double> y(P.N(), 0.0); for (int k = 0; k < P.N(); ++k) if (agg[k] >= 0) y[k] = ec[agg[k]];
                if (smooth) { auto b = BF(y); for (int k = 0; k < P.N(); ++k) if (F[k]) y[k] -= M[k] * b[k]; } return y; };
            auto restrict_ = [&](const std::vector<double>& y) {   // P_s^T S y
                std::vector<double> t(P.N()); for (int k = 0; k < P.N(); ++k) t[k] = F[k] ? P.S[k] * y[k] : 0.0;
                if (smooth) { std::vector<double> my(P.N()); for (int k = 0; k < P.N(); ++k) my[k] = F[k] ? M[k] * y[k] : 0.0; auto b = BF(my); for (int k = 0; k < P.N(); ++k) if (F[k]) t[k] -= P.S[k] * b[k]; }
                std::vector<double> c(nc, 0.0); for (int k = 0; k < P.N(); ++k) if (agg[k] >= 0) c[agg[k]] += t[k]; return c; };
            auto Ac = [&](const std::vector<double>& x) { return restrict_(BF(prolong(x))); };
            std::vector<double> rF = r; for (int k = 0; k < P.N(); ++k) if (!F[k]) rF[k] = 0;
            auto b = restrict_(rF);
            std::vector<double> x(nc, 0.0), rr = b, p = b; double rs = 0; for (double v : rr) rs += v * v; double rs0 = rs;
            for (int cg = 0; cg < 300 && rs > 1e-16 * rs0; ++cg) { auto Ap = Ac(p); double pAp = 0; for (int i = 0; i < nc; ++i) pAp += p[i] * Ap[i];
                if (pAp <= 0) break; double al = rs / pAp; double rn = 0; for (int i = 0; i < nc; ++i) { x[i] += al * p[i]; rr[i] -= al * Ap[i]; rn += rr[i] * rr[i]; }
                for (int i = 0; i < nc; ++i) p[i] = rr[i] + rn / rs * p[i]; rs = rn; }
            auto c = prolong(x);
            zsave = z; Esave = E; pending = true;
            for (int k = 0; k < P.N(); ++k) if (F[k]) z[k] = std::max(z[k] + c[k], 0.0);
            prev = z; w = 1; since = 0; st.coarse++; st.walks += smooth ? 2 : 0;
            continue;
        }
        if (cheb && since == 2) w = 2 / (2 - rho_c * rho_c); else if (cheb && since > 2) w = 4 / (4 - rho_c * rho_c * w);
        jacobi(P, z, prev, r, cheb && since >= 2 ? w : 1.0);
        since++;
    }
    return st;
}

static std::vector<char> read_all(const std::string& f) { std::ifstream in(f, std::ios::binary); return {std::istreambuf_iterator<char>(in), {}}; }

int main(int argc, char** argv) {
    if (argc < 5) { std::fprintf(stderr, "usage: tl CHECKPOINT BOUNDARY.bin SPACING STEPS [tank x y z]\n"); return 2; }
    auto cp = read_all(argv[1]); auto bb = read_all(argv[2]); dx = std::atof(argv[3]); int steps = std::atoi(argv[4]);
    double TX = argc > 7 ? std::atof(argv[5]) : 0.1, TY = argc > 7 ? std::atof(argv[6]) : 0.2, TZ = argc > 7 ? std::atof(argv[7]) : 0.02;
    h = 2 * dx; m = rho0 * dx * dx * dx; sig = 8 / (PI * h * h * h);
    // checkpoint: "RANRYUCP", u32 version, u64 header length, JSON header; entries in order.
    uint64_t hl; std::memcpy(&hl, cp.data() + 12, 8); std::string hdr(cp.data() + 20, hl);
    size_t off = 20 + hl; std::map<std::string, std::pair<size_t, size_t>> ent;
    for (size_t p = hdr.find("\"entries\""); (p = hdr.find("{\"bytes\":", p)) != std::string::npos; ) {
        size_t bytes = std::stoull(hdr.substr(p + 9)); size_t q = hdr.find("\"name\":\"", p) + 8; size_t e = hdr.find('"', q);
        ent[hdr.substr(q, e - q)] = {off, bytes}; off += bytes; p = e;
    }
    State st; int n = int(ent["fluid.positions"].second / 16);
    const float* fp = reinterpret_cast<const float*>(cp.data() + ent["fluid.positions"].first);
    const float* fv = reinterpret_cast<const float*>(cp.data() + ent["fluid.velocities"].first);
    const float* fk = reinterpret_cast<const float*>(cp.data() + ent["fluid.carried.Warm"].first);
    for (int i = 0; i < n; ++i) { st.x.push_back({fp[4 * i], fp[4 * i + 1], fp[4 * i + 2]}); st.v.push_back({fv[4 * i], fv[4 * i + 1], fv[4 * i + 2]}); st.kappa.push_back(fk[2 * i]); st.kappa_v_impulse.push_back(fk[2 * i + 1]); }
    const float* b4 = reinterpret_cast<const float*>(bb.data()); int nb = int(bb.size() / 16);
    for (int b = 0; b < nb; ++b) bx.push_back({b4[4 * b], b4[4 * b + 1], b4[4 * b + 2]});
    glo = {-4 * dx, -4 * dx, -4 * dx}; ghi = {TX + 4 * dx, TY + 4 * dx, TZ + 4 * dx};
    bgrid.build(bx, h, glo, ghi);
    bpsi.assign(nb, 0.0);
    for (int b = 0; b < nb; ++b) { double s = 0; bgrid.near(bx[b], [&](int c) { double r = len(bx[b] - bx[c]); if (r < h) s += W(r); });
        bpsi[b] = rho0 * std::min(1 / s, double(b4[4 * b + 3])); }
    // rows' warm start: hydrostatic at the fluid's top (the engine's initial_boundary_kappa), refined by the model's steps
    double top = 0; for (auto& p : st.x) top = std::max(top, p.y);
    st.kappa_b.assign(nb, 0.0); for (int b = 0; b < nb; ++b) st.kappa_b[b] = std::max(9.81 * (top - bx[b].y) / rho0, 0.0);
    if (getenv("COMPL")) complementarity = true; if (getenv("W")) w_dens = std::atof(getenv("W")); if (getenv("WV")) w_v = std::atof(getenv("WV"));
    double dt0 = argc > 8 ? std::atof(argv[8]) : 1.0 / 60 / 13;
    int warm = argc > 9 ? std::atoi(argv[9]) : 20;
    std::printf("fluid %d, boundary %d, dx %g, dt %g, %d warm-up steps then %d measured\n", n, nb, dx, dt0, warm, steps);
    std::vector<double> factors = {1, 2, 4};
    for (int s = 0; s < warm + steps; ++s) {
        std::vector<double> z0, kv; std::vector<int> row_of_b; std::vector<V> vstar; int div_it = 0;
        State keep = st;
        Problem P = prepare(st, dt0, z0, row_of_b, vstar, kv, div_it);
        std::vector<double> z = z0; Stats sh = shipped(P, z);
        bool report = s >= warm;
        if (report) {
            std::printf("step %d: rows %d div %d | shipped walks %d (it %d, err %.2e peak %.2e%s)", s, P.R, div_it, sh.walks, sh.iterations, sh.err, sh.peak, sh.converged ? "" : " CAP");
            for (double f : factors) {
                std::vector<double> zz, kk; std::vector<int> rb; std::vector<V> vs; int di = 0; State tmp = keep;
                Problem Q = f == 1 ? P : prepare(tmp, dt0 * f, zz, rb, vs, kk, di); if (f == 1) zz = z0;
                if (getenv("COLD")) { double c = std::atof(getenv("COLD")); for (auto& q : zz) q *= c; }
                if (f != 1) { std::vector<double> t = zz; Stats a = shipped(Q, t); std::printf(" | x%g: div %d shipped %d%s", f, di, a.walks, a.converged ? "" : "C"); }
                if (!getenv("NOVAR")) for (double H : {4 * dx, 8 * dx}) for (int nu : {3, 6}) for (int sm : {0, 1}) {
                    std::vector<double> t = zz; Stats a = two_level_sa(Q, st.x, t, H, nu, true, 1, sm);
                    std::printf(" %s(H%g,nu%d) %d%s/%dc%dr", sm ? "SA" : "UA", H / dx, nu, a.walks, a.converged ? "" : "C", a.coarse, a.rejected);
                }
                if (getenv("FRAC")) {   // how much of the step's error energy one coarse correction, or one Jacobi iteration, removes
                    std::vector<double> t = zz; int me = max_it; double se = eta, sp = eta_p; max_it = 3000; eta = 1e-8; eta_p = 1e-6;
                    Stats x = shipped(Q, t); max_it = me; eta = se; eta_p = sp;
                    double Es = Q.energy(t, Q.apply(t)), E0 = Q.energy(zz, Q.apply(zz));
                    std::vector<double> j = zz, pv = zz; auto r0 = Q.residual(zz, Q.apply(zz)); jacobi(Q, j, pv, r0, 1.0); double Ej = Q.energy(j, Q.apply(j));
                    std::printf("\n  FRAC x%g: tight solve %d it (err %.1e), E0-E* %.3e; one Jacobi removes %.1f %%", f, x.iterations, x.err, E0 - Es, 100 * (E0 - Ej) / (E0 - Es));
                    for (double H : {4 * dx, 8 * dx}) for (int sm : {0, 1}) { std::vector<double> c = zz; int mi = max_it; max_it = 2;
                        two_level_sa(Q, st.x, c, H, 1000, false, 0, sm); max_it = mi;   // it 0: the coarse correction; it 1 evaluates it
                        double Ec = Q.energy(c, Q.apply(c)); std::printf("; %s H%g removes %.1f %%", sm ? "SA" : "UA", H / dx, 100 * (E0 - Ec) / (E0 - Es)); }
                    double ez = 0; { std::vector<double> zero(Q.N(), 0.0); ez = Q.energy(zero, Q.apply(zero)); }
                    std::printf("; E(0)-E* %.3e (the warm start's error is %.1f %% of the cold start's)\n", ez - Es, 100 * (E0 - Es) / (ez - Es));
                }
                if (getenv("SYNTH") && f == 1) {   // a smooth known solution: s = -B z_true, z_true hydrostatic
                    Problem Y = Q; double top = 0; for (auto& p : st.x) top = std::max(top, p.y);
                    std::vector<double> zt(Y.N()); for (int k = 0; k < Y.N(); ++k) { V p = k < Y.n ? st.x[k] : Y.xrow[k - Y.n]; zt[k] = std::atof(getenv("SYNTH")) * std::max(9.81 * (top - p.y) / rho0, 0.0); }
                    auto Bt = Y.apply(zt); for (int k = 0; k < Y.N(); ++k) Y.src[k] = -Bt[k];
                    for (double H : {4 * dx, 8 * dx}) for (int nu : {3, 6}) for (int sm : {0, 1}) {
                        std::vector<double> t(Y.N(), 0.0); Stats a = two_level_sa(Y, st.x, t, H, nu, true, 1, sm);
                        std::printf("\n  SYNTH %s(H%g,nu%d) %d%s/%dc%dr", sm ? "SA" : "UA", H / dx, nu, a.walks, a.converged ? "" : "C", a.coarse, a.rejected); }
                    std::vector<double> t(Y.N(), 0.0); Stats a = shipped(Y, t); std::printf("\n  SYNTH shipped %d%s (err %.2e peak %.2e)\n", a.walks, a.converged ? "" : "C", a.err, a.peak);
                }
                if (getenv("TRACE") && f == std::atof(getenv("TRACE"))) {
                    auto Bz = Q.apply(zz); auto r = Q.residual(zz, Bz); std::vector<int> id(Q.n); for (int i = 0; i < Q.n; ++i) id[i] = i;
                    std::sort(id.begin(), id.end(), [&](int a, int b) { return r[a] > r[b]; });
                    std::printf("\n");
                    for (int q = 0; q < 8; ++q) { int i = id[q]; V p = st.x[i]; double wall = std::min({p.x, 0.1 - p.x, p.y, p.z, 0.02 - p.z});
                        std::printf("    top r %.3e at (%.4f %.4f %.4f) wall %.2f dx, nbrs %d, kappa0 %.3e, |v| %.3f, s %.3e\n", r[i] / rho0, p.x, p.y, p.z, wall / dx, Q.neighbours[i], zz[i], len(st.v[i]), -Q.src[i] / rho0); }
                    trace = true; std::vector<double> t = zz; shipped(Q, t); t = zz; two_level_sa(Q, st.x, t, 8 * dx, 3, true, 1, true); trace = false;
                }
            }
            std::printf("\n"); std::fflush(stdout);
        }
        auto a = accel_of(P, z);
        double vmax = 0;
        for (int i = 0; i < n; ++i) { st.v[i] = vstar[i] + dt0 * a[i]; st.x[i] = st.x[i] + dt0 * st.v[i]; st.kappa[i] = z[i]; st.kappa_v_impulse[i] = dt0 * kv[i]; vmax = std::max(vmax, len(st.v[i])); }
        st.dt_prev = dt0;
        for (size_t b = 0; b < bx.size(); ++b) st.kappa_b[b] = row_of_b[b] >= 0 ? z[P.n + row_of_b[b]] : 0.0;
        static long tot_it = 0, tot_div = 0, cnt = 0; tot_it += sh.iterations; tot_div += div_it; cnt++;
        if (s == warm + steps - 1) std::printf("SUMMARY W %g WV %g dt %g: %ld steps, density iterations %.2f a step, divergence %.2f, vmax %.3f\n", w_dens, w_v, dt0, cnt, double(tot_it) / cnt, double(tot_div) / cnt, vmax);
        int holes = 0, deep = 0; { double top = 0; for (auto& p : st.x) top = std::max(top, p.y);
            for (int i = 0; i < n; ++i) if (st.x[i].y < top - 0.01) { deep++; holes += z[i] == 0; } }
        if (!report) std::printf("holes %d of %d deep; ", holes, deep);
        if (!report) std::printf("warm-up step %d: div %d, shipped iterations %d, err %.2e peak %.2e, vmax %.3f\n", s, div_it, sh.iterations, sh.err, sh.peak, vmax);
    }
}
