// fdm_verification: runs the FDM verification problems (docs/theory/fdm.md §2)
// with the library directly, prints the table of computed vs closed-form
// values, and optionally writes it as markdown and runs the mesh-refinement
// study. Exit status 1 if any row fails (or, with --refinement, if an error
// does not fall with refinement), 2 for a usage error.
//
//   fdm_verification                               all problems, unit meshes
//   fdm_verification --problem kirsch --level slow one problem, finer mesh
//   fdm_verification --refinement --write docs/verification.md
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "dfc/fdm/verification/problems.hpp"
#include "dfc/fdm/verification/report.hpp"

namespace {

using namespace dfc::fdm::verification;

constexpr int kRefinementLevels = 3;

struct Options {
  std::vector<const VerificationProblem*> problems;
  std::string level = "unit";  // "unit", "slow" or a number
  std::string write_path;
  bool refinement = false;
  bool list = false;
  std::string command;
};

const char* kUsage =
    "usage: fdm_verification [--problem KEY]... [--level unit|slow|N] [--refinement] [--write FILE] [--list]\n"
    "  --problem KEY   run only this problem (repeatable; default: all)\n"
    "  --level L       mesh level: unit (fast, the CTest 'unit' variant), slow (finer), or a number 0, 1, 2, ...\n"
    "  --refinement    also run the mesh-refinement study (levels 0-2) of the problems marked for it\n"
    "  --write FILE    write the markdown report (table, tolerances, refinement) to FILE\n"
    "  --list          list the problems\n";

int level_of(const VerificationProblem& p, const std::string& level) {
  if (level == "unit") return p.unit_level;
  if (level == "slow") return p.slow_level;
  return std::stoi(level);
}

bool parse(int argc, char** argv, Options& o) {
  o.command = "fdm_verification";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    o.command.append(" ").append(arg);
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      o.command.append(" ").append(argv[i + 1]);
      return argv[++i];
    };
    if (arg == "--problem") {
      const std::string key = value();
      const VerificationProblem* p = find_verification_problem(key);
      if (p == nullptr) throw std::invalid_argument("unknown problem '" + key + "'; see --list");
      o.problems.push_back(p);
    } else if (arg == "--level") {
      o.level = value();
      if (o.level != "unit" && o.level != "slow" && o.level.find_first_not_of("0123456789") != std::string::npos)
        throw std::invalid_argument("--level expects unit, slow or a number, got '" + o.level + "'");
    } else if (arg == "--write") {
      o.write_path = value();
    } else if (arg == "--refinement") {
      o.refinement = true;
    } else if (arg == "--list") {
      o.list = true;
    } else if (arg == "--help" || arg == "-h") {
      std::cout << kUsage;
      return false;
    } else {
      throw std::invalid_argument("unknown argument '" + arg + "'");
    }
  }
  if (o.problems.empty())
    for (const VerificationProblem& p : verification_problems()) o.problems.push_back(&p);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    if (!parse(argc, argv, options)) return 0;
  } catch (const std::exception& e) {
    std::cerr << "fdm_verification: " << e.what() << "\n" << kUsage;
    return 2;
  }
  if (options.list) {
    for (const VerificationProblem& p : verification_problems())
      std::cout << p.key << "  " << p.title << " (" << p.reference << "), tolerance " << 100.0 * p.tolerance << " %, unit level "
                << p.unit_level << ", slow level " << p.slow_level << (p.refinement_study ? ", in the refinement study" : "") << "\n";
    return 0;
  }
  bool ok = true;
  try {
    // 1. The verification table.
    std::vector<ProblemRun> runs;
    for (const VerificationProblem* p : options.problems) {
      const int level = level_of(*p, options.level);
      runs.push_back({p, level, p->run(level)});
      std::cout << text_table({runs.back()}) << std::flush;
      ok = ok && runs.back().result.passed();
    }
    // 2. The refinement study.
    std::vector<RefinementSeries> series;
    if (options.refinement) {
      for (const VerificationProblem* p : options.problems) {
        if (!p->refinement_study) continue;
        RefinementSeries s{p, {}};
        for (int level = 0; level < kRefinementLevels; ++level) s.runs.push_back({p, level, p->run(level)});
        ok = ok && s.error_falls();
        series.push_back(std::move(s));
      }
      std::cout << "\nmesh refinement\n" << text_refinement_table(series);
    }
    // 3. The markdown report.
    if (!options.write_path.empty()) {
      std::ofstream file(options.write_path);
      file << markdown_report(runs, series, options.command);
      if (!file) {
        std::cerr << "fdm_verification: cannot write " << options.write_path << "\n";
        return 2;
      }
      std::cout << "wrote " << options.write_path << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "fdm_verification: " << e.what() << "\n";
    return 1;
  }
  std::cout << (ok ? "all verification rows pass\n" : "VERIFICATION FAILED\n");
  return ok ? 0 : 1;
}
