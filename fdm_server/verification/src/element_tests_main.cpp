// fdm_element_tests — laboratory element tests of the FDM's constitutive
// models at one material point, written as CSV for plotting
// (tools/plot_element_tests.py → docs/figures/, docs/fdm_models.md).
//
//   fdm_element_tests --out DIR
//
// It drives the models with fdm::MaterialPointDriver, the driver the model
// tests use (tests/fdm/*_model_test.cpp), on materials read by the scenario
// parser (load_fdm_material), so the curves are what a scenario would get:
//   mohr_coulomb: drained triaxial at σ3 = 100 and 300 kPa, oedometer;
//   structured_cam_clay, preset chalk_snw (Ciantia et al. 2024 Table 2): drained triaxial
//   at σ3 = 0.5, 1.5 and 3 MPa, oedometer.
// One CSV per path: axial_strain, volumetric_strain (compression positive),
// p_pa, q_pa, sigma_axial_pa, sigma_lateral_pa (compression positive).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "dfc/fdm/fdm_config.hpp"
#include "dfc/constitutive/material_point_driver.hpp"

namespace {

using dfc::constitutive::MaterialPointDriver;

// A dense Mohr-Coulomb rock-like soil: E = 100 MPa, ν = 0.25, c = 20 kPa,
// φ = 30°, ψ = 10°, σt = 10 kPa (the values of tests/constitutive/mohr_coulomb_model_test.cpp's kind).
const char* kMohrCoulomb = R"({"model": "mohr_coulomb", "density_kg_m3": 2000, "young_modulus_pa": 1e8, "poisson_ratio": 0.25,
  "cohesion_pa": 2e4, "friction_angle_deg": 30, "dilation_angle_deg": 10, "tensile_strength_pa": 1e4})";
const char* kChalk = R"({"preset": "chalk_snw"})";

struct Path {
  std::string file;
  std::string material;
  double confinement_pa;   // initial isotropic stress, compression positive
  bool triaxial;           // else oedometer
  double axial_strain;     // final compressive axial strain
  int steps;
};

void write_path(const std::filesystem::path& dir, const Path& path) {
  const dfc::fdm::Material material = dfc::fdm::load_fdm_material(nlohmann::json::parse(path.material));
  MaterialPointDriver driver(*material.model, dfc::fdm::SymTensor::isotropic(-path.confinement_pa));
  std::ofstream out(dir / path.file);
  out << "axial_strain,volumetric_strain,p_pa,q_pa,sigma_axial_pa,sigma_lateral_pa\n";
  const auto row = [&] {
    char line[256];
    std::snprintf(line, sizeof line, "%.9e,%.9e,%.9e,%.9e,%.9e,%.9e\n", -driver.strain().zz, driver.volumetric_strain(),
                  driver.mean_pressure(), driver.deviatoric_stress(), -driver.stress().zz, -driver.stress().xx);
    out << line;
  };
  row();
  const double increment = -path.axial_strain / path.steps;
  for (int step = 0; step < path.steps; ++step) {
    if (path.triaxial) {
      driver.triaxial_step(increment);
    } else {
      driver.oedometer_step(increment);
    }
    row();
  }
  std::cout << (dir / path.file).string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 || std::string(argv[1]) != "--out") {
    std::cerr << "usage: fdm_element_tests --out DIR  (writes one CSV per element-test path)\n";
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[2];
    std::filesystem::create_directories(dir);
    const Path paths[] = {
        {"mohr_coulomb_triaxial_100kpa.csv", kMohrCoulomb, 100e3, true, 0.03, 3000},
        {"mohr_coulomb_triaxial_300kpa.csv", kMohrCoulomb, 300e3, true, 0.03, 3000},
        {"mohr_coulomb_oedometer.csv", kMohrCoulomb, 10e3, false, 0.03, 3000},
        {"chalk_snw_triaxial_500kpa.csv", kChalk, 0.5e6, true, 0.05, 5000},
        {"chalk_snw_triaxial_1500kpa.csv", kChalk, 1.5e6, true, 0.05, 5000},
        {"chalk_snw_triaxial_3000kpa.csv", kChalk, 3.0e6, true, 0.05, 5000},
        {"chalk_snw_oedometer.csv", kChalk, 0.1e6, false, 0.05, 5000},
    };
    for (const Path& path : paths) write_path(dir, path);
  } catch (const std::exception& e) {
    std::cerr << "fdm_element_tests: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
