#include <zraka/image/image_error.hpp>

#include <doctest/doctest.h>

#include <cmath>

using namespace zraka;

TEST_CASE("image_error: RMSE, relative MSE and channel means of known differences") {
  image ref(4, 2, rgb(1.0f)), a(4, 2, rgb(1.0f));
  CHECK(rmse(a, ref) == 0);
  CHECK(relmse(a, ref) == 0);
  a.at(0, 0) = rgb(1.0f, 1.0f, 4.0f);  // one channel of one pixel off by 3
  // RMSE = sqrt(9 / (8 pixels * 3 channels)); relMSE = 9 / 1.01 / 24 (ref^2 + 0.01 = 1.01).
  CHECK(rmse(a, ref) == doctest::Approx(std::sqrt(9.0 / 24)).epsilon(1e-15));  // double sums
  CHECK(relmse(a, ref) == doctest::Approx(9.0 / 1.01 / 24).epsilon(1e-15));
  CHECK(channel_mean(a).z == doctest::Approx((7 + 4) / 8.0).epsilon(1e-15));
  CHECK(channel_mean(a).x == 1.0);
}

TEST_CASE("image_error: black reference pixels do not divide by zero; huge values stay finite") {
  image ref(2, 2, rgb(0.0f)), a(2, 2, rgb(0.1f));
  CHECK(relmse(a, ref) == doctest::Approx(0.01 / 0.01).epsilon(1e-6));  // (0.1)^2 / 0.01, float 0.1
  image big(2, 2, rgb(3e38f));  // near float's maximum: the squares are taken in double
  CHECK(std::isfinite(rmse(big, ref)));
  CHECK(rmse(big, ref) == doctest::Approx(3e38).epsilon(1e-6));
}

TEST_CASE("image_error: images of different sizes are an error") {
  CHECK_THROWS_AS(rmse(image(2, 2), image(2, 3)), error);
  CHECK_THROWS_AS(relmse(image(3, 2), image(2, 2)), error);
}
