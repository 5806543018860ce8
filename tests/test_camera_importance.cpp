// The pinhole camera's importance (camera_importance.hpp, book 6.2): We and the camera ray's
// direction density integrate to one over the sphere, and a point projects back to the image
// position whose camera ray passes through it.
#include <zraka/cameras/camera_importance.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/sampling/sampling.hpp>

#include <doctest/doctest.h>

using namespace zraka;

namespace {
camera::prepared test_camera(double vfov, double aspect) {
  camera c;
  c.position = {0.3, 1.1, 3.9};
  c.look_at = {-0.2, 0.8, 0};
  c.vfov_degrees = vfov;
  c.aspect = aspect;
  return c.prepare();
}
}  // namespace

TEST_CASE("camera importance: We cos theta and the direction pdf integrate to one") {
  for (const auto& [vfov, aspect] : {std::pair{38.0, 1.0}, std::pair{90.0, 16.0 / 9.0}, std::pair{5.0, 0.5}}) {
    INFO("vfov " << vfov << " aspect " << aspect);
    const camera_importance_t<double> eye(test_camera(vfov, aspect));
    // uniform directions in the cone around the view direction that holds the image
    const double half_diag = std::atan(std::tan(vfov * pi<double> / 360) * std::sqrt(1 + aspect * aspect));
    const double h = 1 - std::cos(half_diag) + 1e-9;
    const onb frame(eye.forward);
    rng g(5);
    estimator_t<double> we, pdf;
    for (int k = 0; k < 400000; ++k) {
      const vec3 w = frame.to_world(sample_cone(g.uniform2(), h));
      const double inv_p = 1 / cone_pdf(h);
      we.add(eye.importance(w) * eye.cos_theta(w) * inv_p);
      pdf.add(eye.pdf_direction(w) * inv_p);
    }
    CHECK(std::abs(we.mean() - 1) < 5 * we.standard_error());
    CHECK(std::abs(pdf.mean() - 1) < 5 * pdf.standard_error());
    // We cos / p = 1: a camera ray carries weight one
    const vec3 w = normalize(vec3(eye.corner + 0.3 * eye.horizontal + 0.8 * eye.vertical - eye.origin));
    CHECK(eye.importance(w) * eye.cos_theta(w) / eye.pdf_direction(w) == doctest::Approx(1).epsilon(1e-12));
    CHECK(eye.importance(-eye.forward) == 0);
  }
}

TEST_CASE("camera importance: image_position inverts generate()") {
  const auto cam = test_camera(38, 4.0 / 3.0);
  const camera_importance_t<double> eye(cam);
  rng g(9);
  for (int k = 0; k < 10000; ++k) {
    const vec2 st = g.uniform2();
    const ray r = cam.generate(st.x, st.y);
    const vec3 p = r.at(0.1 + 10 * g.uniform());  // any point along the ray
    const auto back = eye.image_position(normalize(p - eye.origin));
    REQUIRE(back);
    CHECK(back->x == doctest::Approx(st.x).epsilon(1e-9));
    CHECK(back->y == doctest::Approx(st.y).epsilon(1e-9));
  }
  CHECK_FALSE(eye.image_position(-eye.forward));
  camera lens;
  lens.aperture = 0.1;
  CHECK_THROWS_WITH_AS(camera_importance_t<double>(lens.prepare()), doctest::Contains("thin lens"), error);
}
