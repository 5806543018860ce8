// links: yaml-cpp
// microfacet.hpp and the rough materials of material.hpp (book 5.4): chi-square tests of both
// samplers against their own pdfs (conductor: reflection; glass: reflection and transmission,
// entering and leaving) at roughness 0.001, 0.1, 0.5, 1 and incidence 0, 45, 80, 89 degrees;
// the sampled weight against f cos / pdf evaluated independently; reciprocity; the white
// furnace (F = 1 loses exactly the single-scattering energy, against a quadrature); the glass's
// albedo; no NaN at the extremes in float and double; the conductor Fresnel; scene files; the
// renderers that cannot shade them refuse them by name.
#include <zraka/app/chi_square.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/materials/microfacet.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <functional>

using namespace zraka;

namespace {

const double alphas[] = {0.001, 0.1, 0.5, 1.0};
const double angles_deg[] = {0, 45, 80, 89};

vec3 incident(double theta_deg) {
  const double t = theta_deg * pi<double> / 180;
  return {std::sin(t), 0, std::cos(t)};
}

// Chi-square grids that resolve a lobe of any width. For wide lobes (2, below), directions are
// binned over (x, phi) with
// x = m(theta) = theta^2 / (beta^2 + theta^2), theta measured from an axis; equal steps of x
// are narrow near the axis (a width beta) and wide far from it, so a lobe of width ~beta fills
// many bins at any beta. The density over (x, phi) is pdf(w) sin(theta) / m'(theta),
// m'(theta) = 2 theta beta^2 / (beta^2 + theta^2)^2. Samples outside the grid (none here) and
// lost samples share the extra bin of chi_square_2d, which expects what the pdf leaves out.
struct lobe_map {
  double beta;
  double m(double t) const { return t * t / (beta * beta + t * t); }
  double dm(double t) const { return 2 * t * beta * beta / ((beta * beta + t * t) * (beta * beta + t * t)); }
  double inverse(double x) const { return beta * std::sqrt(x / (1 - x)); }
  // sin(theta) / m'(theta), finite at theta = 0 (sin t / t -> 1)
  double jacobian(double t) const {
    const double b2 = beta * beta, q = b2 + t * t;
    return (t > 0 ? std::sin(t) / t : 1.0) * q * q / (2 * b2);
  }
};
double theta_of(const vec3& w) { return std::atan2(std::hypot(w.x, w.y), w.z); }
double phi_of(const vec3& w) {
  const double p = std::atan2(w.y, w.x);
  return p < 0 ? p + 2 * pi<double> : p;
}

// (1) For sharp lobes (alpha 0.001): the gnomonic projection onto the plane tangent to the
// sphere at `axis` (a direction in the xz plane), (p, q) = (w.y, w.e) / w.n with e the in-plane
// direction of elevation; dw = dp dq / (1 + p^2 + q^2)^(3/2). Great circles are straight lines
// there: the horizon is the line q = const, made a bin edge. At grazing incidence the lobe is
// some 50 times thinner across the plane of incidence than along it, which the (p, q) box
// follows: its bounds are the 0.2% and 99.8% quantiles of an independent pilot sample.
template <class Sample, class Pdf>
chi_square_result chi2_plane(Sample&& sample, Pdf&& pdf, const vec3& axis, long n, rng& pilot_rng) {
  const vec3 nz = glm::normalize(axis), ty(0, 1, 0), e = glm::normalize(glm::cross(ty, nz));
  auto project = [&](const vec3& w) -> std::optional<vec2> {
    const double z = glm::dot(w, nz);
    if (!(z > 0)) return std::nullopt;
    return vec2(glm::dot(w, ty) / z, glm::dot(w, e) / z);
  };
  // the horizon, world z = 0: z_n + q e_z = 0 for a direction n + p ty + q e
  const double q_horizon = e.z != 0 ? -nz.z / e.z : 0;  // e.z = 0: the axis is vertical, no horizon
  std::vector<double> ps, qs;
  for (int i = 0; i < 20000; ++i)
    if (const auto w = sample(pilot_rng))
      if (const auto pq = project(*w)) ps.push_back(pq->x), qs.push_back(pq->y);
  std::sort(ps.begin(), ps.end());
  std::sort(qs.begin(), qs.end());
  auto quantile = [](const std::vector<double>& v, double f) { return v[std::size_t(f * double(v.size() - 1))]; };
  double q0 = quantile(qs, 0.002), q1 = quantile(qs, 0.998);
  if (e.z > 0) q0 = std::max(q0, q_horizon);  // the grid ends at the horizon
  if (e.z < 0) q1 = std::min(q1, q_horizon);
  const grid2 grid{40, 40, quantile(ps, 0.002), quantile(ps, 0.998), q0, q1};
  return chi_square_2d([&]() -> std::optional<vec2> {  // the same stream, after the pilot's
        const auto w = sample(pilot_rng);
        if (!w) return std::nullopt;
        return project(*w);
      },
      [&](double p, double q) {
        const double r2 = 1 + p * p + q * q;
        return pdf(glm::normalize(nz + p * ty + q * e)) / (r2 * std::sqrt(r2));
      },
      n, grid, 16);
}

// (2) In the local frame, the upper hemisphere mapped around +z onto x in [0, 1/2] and the
// lower one around -z onto [1/2, 1]: the horizon is a bin edge, so no bin straddles it. A
// large beta (10) makes the bins nearly uniform in cos theta: for lobes along the horizon, which
// are narrow in phi and need ny = 128 (at 32, the 16 x 16 points per bin that integrate the
// pdf miss their shape: X^2 = 8 times its dof at alpha 0.1 and 89 degrees; at 128 it is at its dof).
template <class Sample, class Pdf>
chi_square_result chi2_hemispheres(Sample&& sample, Pdf&& pdf, double beta, long n, int ny = 32) {
  const lobe_map map{beta};
  const double half = map.m(pi<double> / 2);
  const grid2 grid{60, ny, 0, 1, 0, 2 * pi<double>};
  return chi_square_2d(
      [&]() -> std::optional<vec2> {
        const std::optional<vec3> w = sample();
        if (!w) return std::nullopt;
        const double t = theta_of(*w);
        const double x = t <= pi<double> / 2 ? map.m(t) / half / 2 : 1 - map.m(pi<double> - t) / half / 2;
        return vec2(x, phi_of(*w));
      },
      [&](double x, double phi) {
        const bool up = x < 0.5;
        const double tt = map.inverse((up ? x : 1 - x) * 2 * half);  // from the nearer pole
        const double t = up ? tt : pi<double> - tt;
        const vec3 w(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t));
        return pdf(w) * map.jacobian(tt) * 2 * half;
      },
      n, grid, 16);
}

// The BSDF chi-square tests of this file together reject a correct sampler with probability 1%
// (Sidak); counted by hand: 16 conductor + at most 40 glass.
const double level = sidak_level(0.01, 56);

// A point of the quadrature over facet normals: h from (s, v) in [0,1)^2 through the inverse CDF
// of D cos, tan^2 theta = alpha^2 u / (1 - u), with u = 1 - (1 - s)^2 so that the integrable
// 1/sqrt(1 - u) of integrands ~ 1/cos theta_h near the horizon becomes smooth. Returns h and
// the weight 1 / (D(h) cos theta_h) * du/ds, so that sum weight g(h) / N ~ integral g dh.
struct facet_point {
  vec3 h;
  double weight;
};
facet_point facet_quadrature_point(const ggx_t<double>& d, double s, double v) {
  const double a = d.ax, u = 1 - (1 - s) * (1 - s);
  const double tan_t = a * std::sqrt(u / (1 - u)), len = std::hypot(1.0, tan_t);
  const double phi = 2 * pi<double> * v;
  const vec3 h(tan_t / len * std::cos(phi), tan_t / len * std::sin(phi), 1 / len);
  return {h, 2 * (1 - s) / (d.D(h) * h.z)};
}

}  // namespace

// ---------------------------------------------------------------- the distribution
TEST_CASE("microfacet: D is normalised and the visible normals integrate to one") {
  // integral D(h) h.z dh = 1, and integral D_wo(h) dh = 1: Smith's Lambda is the one that makes
  // the visible projected facet area equal wo.z (quadrature over h, facet_quadrature_point).
  for (const double a : alphas)
    for (const double deg : angles_deg) {
      const ggx_t<double> d(a);
      const vec3 wo = incident(deg);
      const int n = 1000, m = 250;
      double norm = 0, visible = 0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
          const facet_point q = facet_quadrature_point(d, (i + 0.5) / n, (j + 0.5) / m);
          norm += d.D(q.h) * q.h.z * q.weight;
          visible += d.visible_pdf(wo, q.h) * q.weight;
        }
      norm /= double(n) * m;
      visible /= double(n) * m;
      INFO("alpha " << a << ", theta_o " << deg << ": " << norm << " " << visible);
      CHECK(norm == doctest::Approx(1).epsilon(1e-6));
      CHECK(visible == doctest::Approx(1).epsilon(1e-3));
    }
}

TEST_CASE("microfacet: the visible-normal sampler follows its density (chi-square)") {
  int k = 0, tests = 0;
  double worst = 1;
  for (const double a : alphas)
    for (const double deg : angles_deg) {
      const ggx_t<double> d(a);
      const vec3 wo = incident(deg);
      rng g(std::uint64_t(100 + k++));
      const auto r = chi2_hemispheres([&]() -> std::optional<vec3> { return d.sample_visible(wo, g.uniform2()); },
                                      [&](const vec3& h) { return d.visible_pdf(wo, h); }, a, 100000,
                                      deg > 80 ? 128 : 32);  // grazing: a lobe narrow in phi
      worst = std::min(worst, r.p_value), ++tests;
      CHECK_MESSAGE(r.p_value > sidak_level(0.01, 16),
                    "alpha " << a << " theta " << deg << ": X^2 " << r.statistic << " dof " << r.dof << " p " << r.p_value
                             << " impossible " << r.impossible);
    }
  std::printf("chi-square, visible normals: %d tests, smallest p %.3g (level %.3g)\n", tests, worst, sidak_level(0.01, 16));
}

// ---------------------------------------------------------------- chi-square of the BSDFs
TEST_CASE("rough conductor: samples follow the pdf (chi-square), 4 roughnesses x 4 angles") {
  int k = 0, tests = 0;
  double worst = 1;
  for (const double a : alphas)
    for (const double deg : angles_deg) {
      const rough_conductor_t<double> f{ggx_t<double>(a), *find_metal("gold")};
      const vec3 wo = incident(deg);
      rng g(std::uint64_t(1000 + k++));
      auto sample_with = [&](rng& gg) -> std::optional<vec3> {
        const auto s = f.sample(wo, gg.uniform2());
        if (!s) return std::nullopt;
        return s->wi;
      };
      auto sample = [&]() { return sample_with(g); };
      auto pdf = [&](const vec3& wi) { return f.pdf(wo, wi); };
      // A sharp lobe in the plane tangent at the mirror direction; wide ones with the horizon
      // as a bin edge; at 89 degrees they hug the horizon: more bins in phi (chi2_hemispheres).
      const auto r = a < 0.1 ? chi2_plane(sample_with, pdf, vec3(-wo.x, -wo.y, wo.z), 100000, g)
                             : chi2_hemispheres(sample, pdf, deg >= 80 ? 10.0 : std::min(1.0, 2 * a), 100000, deg > 80 ? 128 : 32);
      worst = std::min(worst, r.p_value), ++tests;
      CHECK_MESSAGE(r.p_value > level, "alpha " << a << " theta " << deg << ": X^2 " << r.statistic
                                                << " dof " << r.dof << " p " << r.p_value << " impossible " << r.impossible);
    }
  std::printf("chi-square, rough conductor: %d tests, smallest p %.3g (level %.3g)\n", tests, worst, level);
}

TEST_CASE("rough dielectric: samples follow the pdf over the sphere (chi-square), reflection and transmission") {
  // Entering glass (eta 1.5) and leaving it (1/1.5: total internal reflection beyond 42
  // degrees). Wide lobes over the whole sphere at once, the horizon a bin edge; at alpha 0.001
  // one test around the mirror direction and one around the refracted one (each valid alone:
  // all else is the extra bin, which expects the other lobe's share).
  int k = 0, tests = 0;
  double worst = 1;
  for (const double eta : {1.5, 1 / 1.5})
    for (const double a : alphas)
      for (const double deg : angles_deg) {
        const rough_dielectric_t<double> f{ggx_t<double>(a), eta};
        const vec3 wo = incident(deg);
        rng g(std::uint64_t(5000 + k++));
        auto sample_with = [&](rng& gg) -> std::optional<vec3> {
          const vec2 u = gg.uniform2();
          const auto s = f.sample(wo, u, gg.uniform());
          if (!s) return std::nullopt;
          return s->wi;
        };
        auto sample = [&]() { return sample_with(g); };
        auto pdf = [&](const vec3& wi) { return f.pdf(wo, wi); };
        std::vector<chi_square_result> rs;
        if (a >= 0.1) {
          rs.push_back(chi2_hemispheres(sample, pdf, deg >= 80 ? 10.0 : std::min(1.0, 2 * a), 100000, deg > 80 ? 128 : 32));
        } else {
          rs.push_back(chi2_plane(sample_with, pdf, vec3(-wo.x, -wo.y, wo.z), 100000, g));
          if (const auto t = refract(-wo, vec3(0, 0, 1), 1 / eta)) rs.push_back(chi2_plane(sample_with, pdf, *t, 100000, g));
        }
        for (const auto& r : rs) {
          worst = std::min(worst, r.p_value), ++tests;
          CHECK_MESSAGE(r.p_value > level, "eta " << eta << " alpha " << a << " theta " << deg << ": X^2 " << r.statistic
                                                  << " dof " << r.dof << " p " << r.p_value << " impossible " << r.impossible);
        }
      }
  std::printf("chi-square, rough glass: %d tests, smallest p %.3g (level %.3g)\n", tests, worst, level);
}

// ---------------------------------------------------------------- weights, reciprocity
TEST_CASE_TEMPLATE("rough materials: the sampled weight and pdf equal f cos / pdf evaluated independently", T, float, double) {
  // pdfs to rounding; weights are rgb (float) even in double
  const double tol = std::is_same_v<T, float> ? 2e-3 : 1e-9, wtol = std::is_same_v<T, float> ? 2e-3 : 1e-6;
  rng g(7);
  int checked = 0;
  for (const double a : alphas)
    for (const double deg : {0.0, 30.0, 70.0, 89.0}) {
      const vec3_t<T> wo(incident(deg));
      const rough_conductor_t<T> c{ggx_t<T>(T(a)), conductor_fresnel::complex_ior(rgb(0.2f, 0.9f, 1.1f), rgb(3.9f, 2.4f, 2.1f))};
      for (const double eta : {1.5, 1 / 1.5, 2.4}) {
        const rough_dielectric_t<T> gl{ggx_t<T>(T(a)), T(eta)};
        for (int i = 0; i < 200; ++i) {
          const vec2_t<T> u(g.uniform2());
          const T ul = T(g.uniform());
          if (const auto s = gl.sample(wo, u, ul)) {
            const double f = double(gl.f(wo, s->wi)), p = double(gl.pdf(wo, s->wi));
            INFO("glass eta " << eta << " alpha " << a << " theta " << deg << " wi " << s->wi.x << " " << s->wi.y << " " << s->wi.z);
            CHECK(double(s->pdf) == doctest::Approx(p).epsilon(tol));
            CHECK(double(s->weight.x) == doctest::Approx(f * std::abs(double(s->wi.z)) / p).epsilon(wtol));
            CHECK(s->weight.x <= 1.0f);
            ++checked;
          }
          if (eta != 1.5) continue;
          if (const auto s = c.sample(wo, u)) {
            const rgb f = c.f(wo, s->wi);
            const double p = double(c.pdf(wo, s->wi));
            INFO("conductor alpha " << a << " theta " << deg);
            CHECK(double(s->pdf) == doctest::Approx(p).epsilon(tol));
            for (int ch = 0; ch < 3; ++ch)
              CHECK(double(s->weight[ch]) == doctest::Approx(double(f[ch]) * double(s->wi.z) / p).epsilon(wtol));
          }
        }
      }
    }
  CHECK(checked > 1000);
}

TEST_CASE("rough materials: scatter() agrees with brdf_cos() and scatter_pdf() at a tilted hit, and draws three numbers") {
  hit h;
  h.p = vec3(0.3, -0.2, 1.0);
  h.normal = glm::normalize(vec3(0.3, -0.5, 0.8));
  for (const material& m : {material::rough_conductor(0.3, *find_metal("copper")), material::rough_dielectric(0.2, 1.5)})
    for (const bool front : {true, false}) {
      const vec3 d = glm::normalize((front ? -1.0 : 1.0) * h.normal + vec3(0.4, 0.1, -0.2));
      h.set_face(d);
      REQUIRE(h.front_face == front);
      CHECK(has_density(m));
      CHECK_FALSE(is_specular(m));
      rng g(3);
      int n = 0;
      for (int i = 0; i < 2000; ++i) {
        rng before = g;
        const auto s = scatter(m, d, h, g);
        before.uniform2();
        before.uniform();
        CHECK(before.uniform() == g.uniform());  // three numbers, then the same stream
        g = before;
        if (!s) continue;
        ++n;
        const rgb fc = brdf_cos(m, h, -d, s->direction);
        const double p = scatter_pdf(m, h, -d, s->direction);
        CHECK(double(s->pdf) == doctest::Approx(p).epsilon(1e-6));
        CHECK(double(s->weight.y) == doctest::Approx(double(fc.y) / p).epsilon(1e-5));
      }
      CHECK(n > 1500);
    }
}

TEST_CASE("rough materials: reciprocity") {
  rng g(11);
  for (const double a : alphas)
    for (int i = 0; i < 2000; ++i) {
      const vec3 wo = sample_uniform_hemisphere(g.uniform2());
      const vec3 wi = sample_uniform_hemisphere(g.uniform2());
      const rough_conductor_t<double> c{ggx_t<double>(a), *find_metal("gold")};
      const rgb f1 = c.f(wo, wi), f2 = c.f(wi, wo);
      CHECK(f1.x == doctest::Approx(f2.x).epsilon(1e-5));
      const rough_dielectric_t<double> gl{ggx_t<double>(a), 1.5};
      CHECK(gl.f(wo, wi) == doctest::Approx(gl.f(wi, wo)).epsilon(1e-7));
      // Transmission, from outside (index 1) into glass (1.5): seen from wi's side, the frame
      // flips (z -> -z) and eta inverts; f(wo, wi) / eta_wi^2 = f(wi, wo) / eta_wo^2.
      const vec3 wt(wi.x, wi.y, -wi.z);
      const rough_dielectric_t<double> back{ggx_t<double>(a), 1 / 1.5};
      const double there = gl.f(wo, wt), back_f = back.f(vec3(wt.x, wt.y, -wt.z), vec3(wo.x, wo.y, -wo.z));
      INFO("alpha " << a << " wo " << wo.z << " wi " << wt.z);
      CHECK(there / (1.5 * 1.5) == doctest::Approx(back_f / 1.0).epsilon(1e-7));
    }
}

// ---------------------------------------------------------------- furnaces
// The directional albedo of a GGX mirror (F = 1), a(wo) = integral D G2 / (4 cos_o) dwi over the
// upper hemisphere, by quadrature over h as above (wi = reflect(wo, h), dwi = 4 (wo.h) dwh).
static double ggx_albedo_quadrature(double a, const vec3& wo) {
  const ggx_t<double> d(a);
  const int n = 1500, m = 300;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const facet_point q = facet_quadrature_point(d, (i + 0.5) / n, (j + 0.5) / m);
      const double oh = glm::dot(wo, q.h);
      if (!(oh > 0)) continue;
      const vec3 wi = reflect(-wo, q.h);
      if (!(wi.z > 0)) continue;
      sum += d.D(q.h) * d.G2(wo, wi, q.h) * oh / wo.z * q.weight;  // D G2 / (4 cos_o) * 4 (wo.h)
    }
  return sum / (double(n) * m);
}

TEST_CASE("white furnace: a rough conductor with F = 1 loses only the single-scattering energy") {
  // The expected curve (quadrature, printed): 1 at alpha -> 0; at normal incidence it falls to
  // 1 - ln 2 = 0.3069 at alpha = 1 (closed form: there D = 1/pi, Lambda(wi) = (1/cos_i - 1)/2,
  // and wi reflects below the horizon for theta_h > 45 deg, so a = 2 int_{1/sqrt 2}^1
  // (2 mu^2 - 1)/mu dmu). The MC albedo E[weight] must match it within 4 standard errors plus
  // the quadrature's error (~1e-4).
  const rough_conductor_t<double> mirror0{ggx_t<double>(0.001), conductor_fresnel::from_f0(rgb(1))};
  std::printf("GGX single-scattering albedo (F = 1), alpha x theta_o:\n  alpha   ");
  for (const double deg : angles_deg) std::printf("  %5.0f deg", deg);
  std::printf("\n");
  for (const double a : alphas) {
    std::printf("  %5.3f  ", a);
    for (const double deg : angles_deg) {
      const vec3 wo = incident(deg);
      const double expected = ggx_albedo_quadrature(a, wo);
      const rough_conductor_t<double> f{ggx_t<double>(a), conductor_fresnel::from_f0(rgb(1))};
      rng g(std::uint64_t(a * 1000 + deg));
      const long n = 200000;
      double s = 0, s2 = 0;
      for (long i = 0; i < n; ++i) {
        const auto sm = f.sample(wo, g.uniform2());
        const double w = sm ? double(sm->weight.x) : 0.0;
        s += w;
        s2 += w * w;
      }
      const double mean = s / n, se = std::sqrt(std::max(0.0, s2 / n - mean * mean) / n);
      std::printf("  %9.5f", expected);
      INFO("alpha " << a << " theta " << deg << ": quadrature " << expected << ", MC " << mean << " +- " << se);
      CHECK(std::abs(mean - expected) < 4 * se + 2e-4);
      CHECK(expected <= 1 + 1e-9);
      if (a == 0.001 && deg < 89) CHECK(expected > 0.999);
    }
    std::printf("\n");
  }
  CHECK(ggx_albedo_quadrature(1.0, incident(0)) == doctest::Approx(1 - std::log(2.0)).epsilon(1e-4));
  (void)mirror0;
}

TEST_CASE("white furnace: rough glass reflects and transmits at most what comes in, all of it as roughness -> 0") {
  std::printf("rough glass albedo (reflection + transmission), eta 1.5 entering / 1/1.5 leaving:\n");
  for (const double eta : {1.5, 1 / 1.5})
    for (const double deg : {0.0, 45.0, 80.0}) {
      double previous = 2;
      std::printf("  eta %.3f theta %2.0f:", eta, deg);
      for (const double a : alphas) {
        const rough_dielectric_t<double> f{ggx_t<double>(a), eta};
        const vec3 wo = incident(deg);
        rng g(std::uint64_t(77 + a * 100 + deg));
        const long n = 200000;
        double s = 0, s2 = 0;
        for (long i = 0; i < n; ++i) {
          const vec2 u = g.uniform2();
          const auto sm = f.sample(wo, u, g.uniform());
          const double w = sm ? double(sm->weight.x) : 0.0;
          s += w;
          s2 += w * w;
        }
        const double mean = s / n, se = std::sqrt(std::max(0.0, s2 / n - mean * mean) / n);
        std::printf("  %.4f", mean);
        INFO("eta " << eta << " alpha " << a << " theta " << deg << ": albedo " << mean << " +- " << se);
        CHECK(mean <= 1 + 4 * se);
        if (a == 0.001) CHECK(mean > 0.998);
        CHECK(mean <= previous + 4 * se);  // rougher never gains energy
        previous = mean;
      }
      std::printf("\n");
    }
}

// ---------------------------------------------------------------- numerics
TEST_CASE_TEMPLATE("rough materials: no NaN at extreme roughness, grazing angles and extreme random numbers", T, float, double) {
  const T one_minus = one_minus_epsilon<T>;
  const T grazing[] = {T(1), T(0.5), T(1e-3), T(1e-7), T(0)};
  for (const T a : {T(1e-5), T(1e-4), T(1e-3), T(0.1), T(1)})
    for (const T z : grazing) {
      const T s = std::sqrt((T(1) - z) * (T(1) + z));
      const vec3_t<T> wo(s, T(0), z);
      const ggx_t<T> d(a);
      CHECK(!std::isnan(d.lambda(wo)));
      for (const T u0 : {T(0), T(1e-30), T(0.5), one_minus, T(1)})
        for (const T u1 : {T(0), T(0.25), T(0.5), one_minus})
          for (const T ul : {T(0), T(0.5), one_minus}) {
            INFO("alpha " << a << " cos_o " << z << " u " << u0 << " " << u1 << " " << ul);
            const vec3_t<T> h = d.sample_visible(wo, {u0, u1});
            REQUIRE(is_finite(h));
            const T vp = d.visible_pdf(wo, h);
            CHECK(std::isfinite(vp));
            CHECK(vp >= T(0));
            const rough_conductor_t<T> c{d, *find_metal("silver")};
            if (const auto sm = c.sample(wo, {u0, u1})) {
              CHECK(is_finite(sm->wi));
              CHECK(is_finite(sm->weight));
              CHECK(std::isfinite(sm->pdf));
              CHECK(sm->pdf > T(0));
              CHECK(is_finite(c.f(wo, sm->wi)));
            }
            for (const T eta : {T(1.5), T(1) / T(1.5)}) {
              const rough_dielectric_t<T> gl{d, eta};
              if (const auto sm = gl.sample(wo, {u0, u1}, ul)) {
                CHECK(is_finite(sm->wi));
                CHECK(is_finite(sm->weight));
                CHECK(std::isfinite(sm->pdf));
                CHECK(sm->pdf > T(0));
                CHECK(std::isfinite(gl.f(wo, sm->wi)));
                CHECK(std::isfinite(gl.pdf(wo, sm->wi)));
              }
            }
          }
      // Directions on the horizon, below it, and wo = wi: zero or finite, never NaN.
      const rough_dielectric_t<T> gl{d, T(1.5)};
      for (const vec3_t<T>& wi : {vec3_t<T>(1, 0, 0), vec3_t<T>(-1, 0, 0), vec3_t<T>(0, 0, -1), wo, vec3_t<T>(-wo.x, 0, -wo.z)}) {
        CHECK(std::isfinite(gl.f(wo, wi)));
        CHECK(std::isfinite(gl.pdf(wo, wi)));
        CHECK(is_finite(rough_conductor_t<T>{d, *find_metal("gold")}.f(wo, wi)));
      }
    }
}

TEST_CASE("conductor Fresnel: closed forms and presets") {
  // k = 0 is a dielectric seen from the outside: fresnel_dielectric with eta_i / eta_t = 1/eta.
  for (const double eta : {1.33, 1.5, 2.4})
    for (double c = 0.01; c <= 1; c += 0.07)
      CHECK(fresnel_conductor(c, eta, 0.0) == doctest::Approx(fresnel_dielectric(c, 1 / eta)).epsilon(1e-9));
  // Normal incidence: ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2); grazing: 1.
  for (const auto& m : metal_presets())
    for (int ch = 0; ch < 3; ++ch) {
      const double e = m.eta[ch], k = m.k[ch];
      CHECK(fresnel_conductor(1.0, e, k) == doctest::Approx(((e - 1) * (e - 1) + k * k) / ((e + 1) * (e + 1) + k * k)));
      CHECK(fresnel_conductor(0.0, e, k) == 1.0);
      CHECK(fresnel_conductor(1e-9, e, k) > 0.999);
    }
  // Gold is yellow: F0 red > green > blue; silver and aluminium nearly grey, bright.
  const rgb gold = find_metal("gold")->eval(1.0), silver = find_metal("silver")->eval(1.0);
  CHECK(gold.x > gold.y);
  CHECK(gold.y > gold.z);
  CHECK(silver.z > 0.9f);
  CHECK_FALSE(find_metal("unobtainium"));
  // Schlick with F0 = 1 is exactly 1 (the furnace's mirror).
  for (double c = 0; c <= 1; c += 0.1) CHECK(conductor_fresnel::from_f0(rgb(1)).eval(c) == rgb(1));
}

// ---------------------------------------------------------------- scene files and renderers
TEST_CASE("scene file: rough_conductor and rough_dielectric") {
  const auto loaded = parse_scene(R"(
materials:
  gold: {type: rough_conductor, roughness: 0.2, metal: gold}
  custom: {type: rough_conductor, roughness: 0.05, eta: [0.2, 0.9, 1.1], k: [3.9, 2.4, 2.1]}
  tinted: {type: rough_conductor, f0: [0.9, 0.6, 0.5]}
  glass: {type: rough_dielectric, roughness: 0.3, ior: 1.33}
objects:
  - {type: sphere, material: gold}
  - {type: sphere, center: [2, 0, 0], material: custom}
  - {type: sphere, center: [4, 0, 0], material: tinted}
  - {type: sphere, center: [6, 0, 0], material: glass}
)", "rough.yaml");
  const auto& ms = loaded.sc.materials;
  REQUIRE(ms.size() == 5);
  CHECK(ms[1].is<material_kinds::rough_conductor>());
  CHECK(ms[1].get<material_kinds::rough_conductor>()->roughness.alpha == 0.2);
  CHECK(ms[1].get<material_kinds::rough_conductor>()->conductor.eta == find_metal("gold")->eta);
  CHECK(ms[2].get<material_kinds::rough_conductor>()->conductor.k.y == doctest::Approx(2.4));
  CHECK(ms[3].get<material_kinds::rough_conductor>()->conductor.schlick);
  CHECK(ms[3].get<material_kinds::rough_conductor>()->roughness.alpha == ggx_roughness{}.alpha);
  CHECK(parse_scene("materials: {m: {type: rough_conductor}}\nobjects: [{type: sphere, material: m}]", "t.yaml")
            .sc.materials[1].get<material_kinds::rough_conductor>()->conductor.eta == find_metal("silver")->eta);  // the default metal
  CHECK(ms[4].is<material_kinds::rough_dielectric>());
  CHECK(ms[4].get<material_kinds::rough_dielectric>()->ior == doctest::Approx(1.33));
  // The resolved scene reads back to the same materials.
  const auto again = parse_scene(loaded.resolved, "resolved.yaml");
  auto alpha = [](const material& m) {
    const auto* c = m.get<material_kinds::rough_conductor>();
    return c ? c->roughness.alpha : m.get<material_kinds::rough_dielectric>()->roughness.alpha;
  };
  auto eta = [](const material& m) {
    const auto* c = m.get<material_kinds::rough_conductor>();
    return c ? c->conductor.eta : rgb(0);
  };
  for (std::size_t i = 1; i < 5; ++i) {
    CHECK(again.sc.materials[i].kind.index() == ms[i].kind.index());
    CHECK(alpha(again.sc.materials[i]) == doctest::Approx(alpha(ms[i])));
    CHECK(eta(again.sc.materials[i]) == eta(ms[i]));
  }
  // Whitted refuses them by name; the OpenCL packer takes them (tests/test_realtime.cpp renders them).
  scene_t<double> sc = loaded.sc;
  sc.settings.width = sc.settings.height = 4;
  CHECK_THROWS_WITH_AS(check_whitted_scene(sc), doctest::Contains("material 'gold' is a rough_conductor"), error);
  CHECK(pack_scene(sc, 4, 4, path_options{}).features.rough_conductor);
  scene_t<double> glass_only;
  glass_only.add(sphere_t<double>{vec3(0), 1}, glass_only.add_material(material::rough_dielectric(0.1, 1.5)));
  CHECK_THROWS_WITH_AS(check_whitted_scene(glass_only), doctest::Contains("rough_dielectric"), error);
  CHECK(pack_scene(glass_only, 4, 4, path_options{}).features.rough_dielectric);
  // The constructors check their arguments as the scene file does.
  CHECK_THROWS_AS(material::rough_conductor(0, *find_metal("gold")), error);
  CHECK_THROWS_AS(material::rough_conductor(std::nan(""), *find_metal("gold")), error);
  CHECK_THROWS_AS(material::rough_dielectric(1.5, 1.5), error);
  CHECK_THROWS_AS(material::rough_dielectric(0.5, 1.0), error);
}

TEST_CASE("rough materials in the path tracer: naive, nee and mis agree (light sampling through brdf_cos and scatter_pdf)") {
  // A rough gold and a rough glass ball over a grey floor, lit by a quad light: the three
  // integrators estimate the same radiance along fixed rays that hit each ball, within 4
  // standard errors of their difference. nee and mis ask brdf_cos() and scatter_pdf() of the
  // rough materials (the glass also through its transmission), naive only scatter().
  scene sc;
  const int floor = sc.add_material(material::lambertian(rgb(0.5f)));
  const int gold = sc.add_material(material::rough_conductor(0.3, *find_metal("gold")));
  const int glass = sc.add_material(material::rough_dielectric(0.3, 1.5));
  const int lamp = sc.add_material(material::emitter(rgb(10.0f)));
  sc.add(quad{{-4, 0, 4}, {8, 0, 0}, {0, 0, -8}}, floor);
  sc.add(sphere{{-0.7, 0.5, 0}, 0.5}, gold);
  sc.add(sphere{{0.7, 0.5, 0}, 0.5}, glass);
  sc.add(quad{{-1, 2.5, -1}, {2, 0, 0}, {0, 0, 2}}, lamp);
  sc.background = rgb(0.2f);
  for (const double x : {-0.8, 0.6, 0.8}) {  // gold, glass edge, glass middle
    const ray r(vec3(0, 1.0, 4), glm::normalize(vec3(x, 0.45, 0) - vec3(0, 1.0, 4)));
    double mean[3], se[3];
    int k = 0;
    for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
      path_options o;
      o.method = m;
      o.max_depth = 6;
      const path_tracer t(sc, o);
      rng g(std::uint64_t(31 + k));
      std::uint64_t rays = 0;
      const int n = 60000;
      double s = 0, s2 = 0;
      for (int i = 0; i < n; ++i) {
        const rgb L = t(r, g, rays);
        const double v = (double(L.x) + L.y + L.z) / 3;
        s += v;
        s2 += v * v;
      }
      mean[k] = s / n;
      se[k] = std::sqrt(std::max(0.0, s2 / n - mean[k] * mean[k]) / n);
      ++k;
    }
    INFO("x " << x << ": naive " << mean[0] << " +- " << se[0] << ", nee " << mean[1] << " +- " << se[1] << ", mis "
              << mean[2] << " +- " << se[2]);
    CHECK(std::abs(mean[0] - mean[2]) < 4 * std::hypot(se[0], se[2]));
    CHECK(std::abs(mean[1] - mean[2]) < 4 * std::hypot(se[1], se[2]));
    CHECK(mean[2] > 0.05);
  }
}
