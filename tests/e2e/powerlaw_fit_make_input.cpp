// Writes the inputs the powerlaw-fit end-to-end tests need, from seeded portable draws (frac::Rng):
//   powerlaw_fit_make_input text OUT N ALPHA SEED        N values of a continuous power law (x_min = 1), one a line
//   powerlaw_fit_make_input fragments OUT N ALPHA SEED   a 'fragments' file as fragment-count writes it: cell_count
//       35% single cells, the rest a discrete power law from k_min = 2; mass = cells * 1 g * U(0.9, 1.1);
//       /fragments attrs min_cells = 2, total_mass
//   powerlaw_fit_make_input bad-fragments OUT            a fragments file with one zero and one NaN mass
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "analysis/powerlaw_continuous.hpp"
#include "analysis/powerlaw_discrete.hpp"
#include "core/provenance.hpp"
#include "io/header.hpp"
#include "io/output_file.hpp"

using namespace frac;

namespace {

void write_fragments(const std::string& out_path, const std::vector<double>& mass,
                     const std::vector<std::int64_t>& cells, const std::string& command) {
  io::OutputFile out(out_path);
  ToolRun run = start_run("powerlaw_fit_make_input", command);
  io::write_header(out.root(), "fragments", run, out.uuid());
  io::Group g = out.root().create_group("fragments");
  g.write("mass", std::span<const double>(mass), {mass.size()}, "kg");
  g.write("cell_count", std::span<const std::int64_t>(cells), {cells.size()}, "1");
  double total = 0;
  for (double m : mass) total += m;
  g.set_attr("min_cells", std::int64_t{2});
  g.set_attr("total_mass", total);
  out.commit();
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  std::string command;
  for (int k = 0; k < argc; ++k) command += (k ? " " : "") + std::string(argv[k]);
  if ((mode == "text" || mode == "fragments") && argc == 6) {
    const std::string out = argv[2];
    const auto n = static_cast<std::size_t>(std::stoll(argv[3]));
    const double alpha = std::stod(argv[4]);
    Rng rng(std::stoull(argv[5]));
    if (mode == "text") {
      std::FILE* f = std::fopen(out.c_str(), "w");
      if (!f) return 1;
      std::fprintf(f, "# %zu values of a power law, alpha = %g, x_min = 1\n", n, alpha);
      for (std::size_t i = 0; i < n; ++i)
        std::fprintf(f, "%.17g\n", analysis::draw_continuous(1.0, alpha, INFINITY, rng));
      return std::fclose(f) == 0 ? 0 : 1;
    }
    const analysis::DiscreteSampler ds(2, alpha);
    std::vector<std::int64_t> cells(n);
    std::vector<double> mass(n);
    for (std::size_t i = 0; i < n; ++i) {
      cells[i] = rng.uniform() < 0.35 ? 1 : static_cast<std::int64_t>(ds.draw(rng));
      mass[i] = 1e-3 * static_cast<double>(cells[i]) * rng.uniform(0.9, 1.1);
    }
    write_fragments(out, mass, cells, command);
    return 0;
  }
  if (mode == "bad-fragments" && argc == 3) {
    std::vector<double> mass{1e-3, 2e-3, 0.0, 3e-3, std::nan(""), 5e-3, 1e-3, 8e-3, 2e-3, 4e-3, 1e-2, 2e-2};
    std::vector<std::int64_t> cells{1, 2, 1, 3, 1, 5, 1, 8, 2, 4, 10, 20};
    write_fragments(argv[2], mass, cells, command);
    return 0;
  }
  std::cerr << "usage: powerlaw_fit_make_input text|fragments OUT N ALPHA SEED | bad-fragments OUT\n";
  return 2;
}
