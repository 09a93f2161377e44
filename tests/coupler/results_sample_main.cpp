// results_sample OUT.h5: writes a small results file shaped like a pile run
// (the plot-tool columns, particle and grid snapshots) for the tool tests.
#include <exception>
#include <filesystem>
#include <iostream>

#include "dfc/coupler/results_writer.hpp"
#include "results_sample_data.hpp"

int main(int argc, char** argv) {
  using namespace dfc::coupler;
  if (argc != 2) {
    std::cerr << "usage: results_sample OUT.h5\n";
    return 2;
  }
  try {
    const std::filesystem::path path = argv[1];
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    ResultsWriter out(path, {{"name", "sample"}}, {{"coupler", "test"}});
    out.declare_series(testing::sample_columns(), testing::sample_units());
    for (int i = 0; i < 60; ++i) out.append(testing::sample_row(i));
    for (int k = 0; k < 3; ++k) {
      out.write_snapshot("dem", 20 * k, 0.02 * k, "particles", testing::particle_arrays(10, k));
      out.write_snapshot("fdm", 20 * k, 0.02 * k, "grid", testing::grid_arrays(3, 2, 2, k));
    }
    out.set_attribute("summary", R"({"rows": 60})");
    out.close();
    std::cout << out.path().string() << '\n' << out.xdmf_path().string() << '\n';
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "results_sample: " << e.what() << '\n';
    return 1;
  }
}
