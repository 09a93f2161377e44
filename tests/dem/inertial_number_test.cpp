// The inertial number of a loading (inertial_number.hpp; GDR MiDi 2004, da Cruz
// et al. 2005) and the grain scale it reads from the particles, against hand
// calculations.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dfc/dem/inertial_number.hpp"

namespace dfc::dem {
namespace {

TEST(InertialNumber, IsTheShearRateTimesTheGrainPressureTime) {
  // gamma_dot 1/s, d 1 mm, p 1 MPa, rho_s 2500 kg/m3: sqrt(p/rho) = 20 m/s, I = 1e-3 / 20.
  EXPECT_DOUBLE_EQ(inertial_number(1.0, 1e-3, 1e6, 2500.0), 5e-5);
  EXPECT_DOUBLE_EQ(inertial_number(2.0, 1e-3, 4e6, 2500.0), 5e-5);  // twice the rate, four times the pressure
}

TEST(InertialNumber, AnUnloadedTipOrAFreeFallReportTheCap) {
  EXPECT_EQ(inertial_number(1.0, 1e-3, 0.0, 2500.0), unloaded_inertial_number);
  EXPECT_EQ(inertial_number(1.0, 1e-3, -5.0, 2500.0), unloaded_inertial_number);  // the tip pulled, not pushed
  EXPECT_EQ(inertial_number(1e4, 1e-3, 1.0, 2500.0), unloaded_inertial_number);   // I = 500: capped
}

TEST(InertialNumber, TheGrainScaleIsTheMeanDiameterAndTheMassOverTheVolume) {
  ParticleStore particles;
  particles.add_sphere(1, {0.0, 0.0, 0.0}, 1e-3, 2000.0);
  particles.add_sphere(2, {1.0, 0.0, 0.0}, 2e-3, 3000.0);
  const GrainScale g = grain_scale(particles);
  EXPECT_DOUBLE_EQ(g.mean_diameter, 3e-3);
  // (2000 * 1 + 3000 * 8) / (1 + 8) for volumes in units of 4/3 pi (1 mm)^3
  EXPECT_NEAR(g.density, 26000.0 / 9.0, 1e-9 * 26000.0 / 9.0);
  EXPECT_EQ(grain_scale(ParticleStore{}).mean_diameter, 0.0);
}

}  // namespace
}  // namespace dfc::dem
