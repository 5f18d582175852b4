#pragma once
// What wave-speed computes, as library calls the tool and the tests share: the predicted speeds alone
// (`wave-speed --theory ...`), or the fronts measured on a run, compared with the prediction for the same
// material and stretch when the lattice is Mooney-Rivlin there (or, for the DEM, with the plane-stress
// speeds of measured elastic constants). Options left unset are taken from the run: its /parameters
// (the resolved scene rubber-run or dem-run records as string attributes), its mesh (spacing, lattice
// orientation) and its first frame (the homogeneous pre-stretch).
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/mooney_rivlin_waves.hpp"
#include "analysis/wave_speed.hpp"
#include "io/hdf5.hpp"
#include "io/speeds_io.hpp"

namespace frac::analysis {

struct TheoryInputs {
  // "" = automatic (a run: Mooney-Rivlin for rubber when a and b are known, plane stress for the DEM when
  // K and nu are given), "mooney-rivlin", or "dem" (plane stress from measured elastic constants).
  std::string theory;
  std::optional<double> a, b, density;  // Mooney-Rivlin: m^2 s^-2, 1, kg m^-2 (areal)
  std::optional<Stretch> stretch;
  std::optional<double> young, poisson;  // DEM: Pa, 1; density in kg m^-3 (3D) for the DEM
  // Lattice check (Mooney-Rivlin only): spacing Delta, short-bond width u_s, cut-off u_c and its width, m.
  std::optional<double> spacing, short_width, cutoff, cutoff_width;
  std::optional<std::string> rows_along;
  std::vector<double> directions;  // rad (kRadial allowed); theory alone: default x and y
};

// A --theory value: "mooney-rivlin" (or "mr") or "dem"; UsageError naming `option` otherwise.
std::string parse_theory(std::string_view text, std::string_view option);

// The predicted speeds alone (origin "theory"). UsageError naming the missing or bad option.
io::SpeedsRecord predict_speeds(const TheoryInputs& in);

struct RunRequest {
  FrontOptions front;
  bool directions_given = false;  // else from /parameters, or x (radial for the DEM pulse and explosion scenes)
  bool modes_given = false;       // front.modes (empty: automatic) is the user's; else from /parameters, or automatic
  TheoryInputs theory;
};

// Measures the run's fronts and compares them with the prediction where it applies (origin "run").
// `notes` receives one line per default taken from the run and per front that could not be measured.
// InputError when a mode given by the user cannot be timed, or no front at all can.
io::SpeedsRecord measure_and_compare(const io::Group& run, RunRequest req, std::vector<std::string>& notes);

// Every string attribute of /parameters/<tool> (empty when the group is missing).
std::map<std::string, std::string> run_parameters(const io::Group& run, std::string_view tool);

}  // namespace frac::analysis
