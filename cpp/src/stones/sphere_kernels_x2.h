// sphere_kernels.h's law at two contacts at once, in the two lanes of SSE2 registers: every operation of
// apply_law in the same order, on each lane as the scalar code does it (IEEE add, multiply, divide and
// square root round alike in a lane and in a scalar register), so the loads and histories are the
// scalar law's, bit for bit. The branches of the law (an empty spring, a zero tangent, the Coulomb and
// rolling caps) become selections between both outcomes. Why: the law is a chain of square roots and
// divisions, which the divider takes two at a time in one instruction; the contact loop of
// sphere_model.cpp hands it its overlaps in pairs. Without SSE2 the loop keeps the scalar law.
#pragma once

#if defined(__SSE2__)
#define VOFDEM_SPHERE_X2 1
#include <emmintrin.h>

#include "stones/sphere_kernels.h"

namespace vofdem::sphere_kernels::x2 {

// two doubles, lane 0 the first contact's
struct D2 {
  __m128d v;
};
VOFDEM_SPHERE_INLINE D2 operator+(D2 a, D2 b) { return {_mm_add_pd(a.v, b.v)}; }
VOFDEM_SPHERE_INLINE D2 operator-(D2 a, D2 b) { return {_mm_sub_pd(a.v, b.v)}; }
VOFDEM_SPHERE_INLINE D2 operator*(D2 a, D2 b) { return {_mm_mul_pd(a.v, b.v)}; }
VOFDEM_SPHERE_INLINE D2 operator/(D2 a, D2 b) { return {_mm_div_pd(a.v, b.v)}; }
VOFDEM_SPHERE_INLINE D2 operator-(D2 a) { return {_mm_xor_pd(a.v, _mm_set1_pd(-0.0))}; }  // the sign, as -x
VOFDEM_SPHERE_INLINE D2 splat(double x) { return {_mm_set1_pd(x)}; }
VOFDEM_SPHERE_INLINE D2 pair(double a, double b) { return {_mm_set_pd(b, a)}; }
VOFDEM_SPHERE_INLINE D2 sqrt(D2 a) { return {_mm_sqrt_pd(a.v)}; }
// masks: all bits set in a lane where the comparison holds (false for NaN, as the scalar comparison)
VOFDEM_SPHERE_INLINE __m128d operator<(D2 a, D2 b) { return _mm_cmplt_pd(a.v, b.v); }
VOFDEM_SPHERE_INLINE __m128d operator>(D2 a, D2 b) { return _mm_cmpgt_pd(a.v, b.v); }
VOFDEM_SPHERE_INLINE __m128d operator==(D2 a, D2 b) { return _mm_cmpeq_pd(a.v, b.v); }
// mask ? a : b, lane by lane
VOFDEM_SPHERE_INLINE D2 select(__m128d mask, D2 a, D2 b) {
  return {_mm_or_pd(_mm_and_pd(mask, a.v), _mm_andnot_pd(mask, b.v))};
}
VOFDEM_SPHERE_INLINE bool any(__m128d mask) { return _mm_movemask_pd(mask) != 0; }
VOFDEM_SPHERE_INLINE double lane(D2 a, int k) {
  alignas(16) double t[2];
  _mm_store_pd(t, a.v);
  return t[k];
}

// a 3-vector of each lane
struct V2 {
  D2 x, y, z;
};
VOFDEM_SPHERE_INLINE V2 load(const Vec3& a, const Vec3& b) { return {pair(a[0], b[0]), pair(a[1], b[1]), pair(a[2], b[2])}; }
VOFDEM_SPHERE_INLINE void store(V2 v, Vec3& a, Vec3& b) {
  _mm_storel_pd(&a[0], v.x.v), _mm_storeh_pd(&b[0], v.x.v);
  _mm_storel_pd(&a[1], v.y.v), _mm_storeh_pd(&b[1], v.y.v);
  _mm_storel_pd(&a[2], v.z.v), _mm_storeh_pd(&b[2], v.z.v);
}
VOFDEM_SPHERE_INLINE void store(D2 v, double& a, double& b) { _mm_storel_pd(&a, v.v), _mm_storeh_pd(&b, v.v); }
VOFDEM_SPHERE_INLINE V2 operator+(V2 a, V2 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
VOFDEM_SPHERE_INLINE V2 operator-(V2 a, V2 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
VOFDEM_SPHERE_INLINE V2 operator-(V2 a) { return {-a.x, -a.y, -a.z}; }
VOFDEM_SPHERE_INLINE V2 operator*(D2 s, V2 a) { return {s * a.x, s * a.y, s * a.z}; }
VOFDEM_SPHERE_INLINE V2 operator*(V2 a, D2 s) { return {a.x * s, a.y * s, a.z * s}; }
VOFDEM_SPHERE_INLINE V2 operator/(V2 a, D2 s) { return {a.x / s, a.y / s, a.z / s}; }
VOFDEM_SPHERE_INLINE V2 select(__m128d mask, V2 a, V2 b) {
  return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)};
}
// Eigen's order for a 3-vector: (a0 b0 + a1 b1) + a2 b2
VOFDEM_SPHERE_INLINE D2 dot(V2 a, V2 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; }
VOFDEM_SPHERE_INLINE V2 cross(V2 a, V2 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// onto_tangent_plane
VOFDEM_SPHERE_INLINE V2 onto_tangent_plane(V2 v, V2 n) {
  const D2 zero = splat(0.0);
  const D2 length = sqrt(dot(v, v));
  const V2 p = v - dot(v, n) * n;
  const D2 pl = sqrt(dot(p, p));
  const V2 turned = select(pl > zero, p * (length / pl), V2{zero, zero, zero});
  return select(length == zero, v, turned);
}

// root_exceeds
VOFDEM_SPHERE_INLINE __m128d root_exceeds(D2 x, D2 c, D2 root_x) {
  const __m128d below = _mm_and_pd(c > splat(1e-150), x < c * c * splat(1.0 - 1e-12));
  return _mm_andnot_pd(below, root_x > c);
}
// std::max(x, 0.0): x unless x < 0
VOFDEM_SPHERE_INLINE D2 max0(D2 x) { return select(x < splat(0.0), splat(0.0), x); }

// the stones' arrays of DEMSystem (x, z in pos and vel, y apart, the 3D spin)
struct Stones {
  const double *pos, *y, *radius, *vel, *vel_y, *omega;
};
VOFDEM_SPHERE_INLINE V2 centre(const Stones& s, int a, int b) {
  return {pair(s.pos[2 * a], s.pos[2 * b]), pair(s.y[a], s.y[b]), pair(s.pos[2 * a + 1], s.pos[2 * b + 1])};
}
VOFDEM_SPHERE_INLINE V2 velocity(const Stones& s, int a, int b) {
  return {pair(s.vel[2 * a], s.vel[2 * b]), pair(s.vel_y[a], s.vel_y[b]), pair(s.vel[2 * a + 1], s.vel[2 * b + 1])};
}
VOFDEM_SPHERE_INLINE V2 spin(const Stones& s, int a, int b) {
  return {pair(s.omega[3 * a], s.omega[3 * b]), pair(s.omega[3 * a + 1], s.omega[3 * b + 1]),
          pair(s.omega[3 * a + 2], s.omega[3 * b + 2])};
}

// pair_geometry of spheres (stones i and j of a pair, each its own body's centre) at pairs a and b: the
// lanes' bits 0 (a) and 1 (b) set where they touch; the geometry and arms stored for those
VOFDEM_SPHERE_INLINE int pair_geometry(const Stones& s, int ia, int ja, int ib, int jb, const SphereContactLaw& law,
                                       SphereContactGeometry& ga, Vec3& arm_ia, Vec3& arm_ja,
                                       SphereContactGeometry& gb, Vec3& arm_ib, Vec3& arm_jb) {
  const D2 zero = splat(0.0);
  const V2 ci = centre(s, ia, ib), cj = centre(s, ja, jb);
  const D2 ri = pair(s.radius[ia], s.radius[ib]), rj = pair(s.radius[ja], s.radius[jb]);
  const V2 d = cj - ci;
  const D2 dist = sqrt(dot(d, d));
  const D2 delta = ri + rj - dist;
  const int touching = _mm_movemask_pd(delta > zero);
  const V2 n = select(dist > zero, d / dist, V2{zero, zero, splat(1.0)});  // coincident centres: +z
  const V2 point = ci + (ri - splat(0.5) * delta) * n;
  const V2 arm_i = point - ci, arm_j = point - cj;
  const V2 wi = spin(s, ia, ib), wj = spin(s, ja, jb);
  const V2 v_rel = (velocity(s, ia, ib) + cross(wi, arm_i)) - (velocity(s, ja, jb) + cross(wj, arm_j));
  store(n, ga.n, gb.n);
  store(delta, ga.delta, gb.delta);
  store(point, ga.point, gb.point);
  store(v_rel, ga.v_rel, gb.v_rel);
  store(wi - wj, ga.w_rel, gb.w_rel);
  store(arm_i, arm_ia, arm_ib);
  store(arm_j, arm_ja, arm_jb);
  ga.mu = gb.mu = law.friction;
  ga.mu_r = gb.mu_r = law.rolling_friction;
  return touching;
}

// one contact's inputs and outputs
struct Contact {
  const SphereContactGeometry* g;
  const PairConstants* c;
  const Vec3* arm_i;
  const Vec3* arm_j;
  SphereContactHistory* h;
  SphereContactLoads* out;  // force_i, torque_i, torque_j, energy_spring, power_damp, energy_slip set
};

// apply_law at contacts a and b (the law's mu and mu_r are the loop's, the same at both)
VOFDEM_SPHERE_INLINE void apply_law(const Contact& a, const Contact& b, const SphereContactLaw& law, double dt) {
  const D2 zero = splat(0.0);
  const V2 n = load(a.g->n, b.g->n);
  const D2 delta = pair(a.g->delta, b.g->delta);
  const V2 v_rel = load(a.g->v_rel, b.g->v_rel);
  const double kn_s = law.stiffness_normal, kt_s = law.stiffness_ratio * kn_s;
  const D2 kn = splat(kn_s), kt = splat(kt_s), dt2 = splat(dt);
  const D2 cn = pair(a.c->cn, b.c->cn), ct = pair(a.c->ct, b.c->ct);
  const D2 vn = dot(v_rel, n);
  const V2 vt = v_rel - vn * n;
  const D2 fn = kn * delta + cn * vn;
  // tangential
  V2 spring = onto_tangent_plane(load(a.h->spring, b.h->spring), n);
  spring = spring + vt * dt2;
  V2 ft = -kt * spring - ct * vt;
  const D2 cap_t = splat(law.friction) * max0(fn);
  D2 energy_slip = zero;
  const D2 ft2 = dot(ft, ft);
  const __m128d slide = root_exceeds(ft2, cap_t, sqrt(ft2));
  if (any(slide)) {
    const D2 f = sqrt(ft2);
    const V2 step = vt * dt2;
    const V2 before = spring - step;
    const V2 ft_cap = ft * (cap_t / f);
    const V2 spring_cap =
        kt_s > 0.0 ? V2(-(ft_cap + ct * vt) / kt) : V2{zero, zero, zero};
    const V2 back = spring_cap - step;
    const D2 slip = energy_slip + splat(0.5) * kt * (dot(before, before) - dot(back, back));  // slip_energy
    ft = select(slide, ft_cap, ft);
    spring = select(slide, spring_cap, spring);
    energy_slip = select(slide, slip, energy_slip);
  }
  const V2 force = -fn * n + ft;
  V2 torque_i = cross(load(*a.arm_i, *b.arm_i), force);
  V2 torque_j = cross(load(*a.arm_j, *b.arm_j), -force);
  D2 power_damp = zero + (cn * vn * vn + ct * dot(vt, vt));
  D2 energy_spring = zero + (splat(0.5) * kn * delta * delta + splat(0.5) * kt * dot(spring, spring));
  if (law.rolling_friction > 0.0) {
    const V2 w_rel = load(a.g->w_rel, b.g->w_rel);
    const V2 wr = w_rel - dot(w_rel, n) * n;
    const D2 kr = pair(a.c->kr, b.c->kr), cr = pair(a.c->cr, b.c->cr);
    V2 rolling = onto_tangent_plane(load(a.h->rolling, b.h->rolling), n);
    rolling = rolling - kr * dt2 * wr;
    const D2 cap_r = splat(law.rolling_friction) * pair(a.c->r_eff, b.c->r_eff) * max0(fn);
    const D2 r2 = dot(rolling, rolling);
    const D2 m = sqrt(r2);
    const __m128d full = root_exceeds(r2, cap_r, m);
    const __m128d kr_on = kr > zero;
    // full mobilisation: the spring slips to the cap, the damper is off
    const V2 rolling_cap = rolling * (cap_r / m);
    const D2 slip = energy_slip + select(kr_on, splat(0.5) * (m * m - cap_r * cap_r) / kr, zero);
    energy_slip = select(full, slip, energy_slip);
    power_damp = select(full, power_damp, power_damp + cr * dot(wr, wr));
    const V2 moment = select(full, rolling_cap, rolling - cr * wr);
    rolling = select(full, rolling_cap, rolling);
    energy_spring = energy_spring + select(kr_on, splat(0.5) * dot(rolling, rolling) / kr, zero);
    torque_i = torque_i + moment;
    torque_j = torque_j - moment;
    store(rolling, a.h->rolling, b.h->rolling);
  }
  store(spring, a.h->spring, b.h->spring);
  store(force, a.out->force_i, b.out->force_i);
  store(torque_i, a.out->torque_i, b.out->torque_i);
  store(torque_j, a.out->torque_j, b.out->torque_j);
  store(energy_spring, a.out->energy_spring, b.out->energy_spring);
  store(power_damp, a.out->power_damp, b.out->power_damp);
  store(energy_slip, a.out->energy_slip, b.out->energy_slip);
}

}  // namespace vofdem::sphere_kernels::x2
#endif
