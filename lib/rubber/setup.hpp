#pragma once
// A rubber-run scene (data/scenes/stretch.ini, wave.ini; docs/rubber-run.md lists every key), read
// through core/scene.hpp so that every resolved value is recorded and unknown keys are refused, and
// what follows from it for a given mesh: the bond law in SI, the node mass, the far-field state, the
// time step checked against ω_max, the Mooney-Rivlin and lattice wave speeds, and warnings.
//
// SI units everywhere. Lengths of the law default to the note's values in units of the mesh's
// spacing Δ (u_s = 0.1Δ, cut-off width 0.05Δ, u_c = 3.5Δ), so a scene without them works on any mesh.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "continuum/mooney_rivlin.hpp"
#include "core/scene.hpp"
#include "dynamics/integrator.hpp"
#include "mesh/node_mesh.hpp"
#include "rubber/bond_law.hpp"
#include "rubber/forces.hpp"
#include "rubber/probe.hpp"

namespace frac::rubber {

struct RubberScene {
  // [material]
  double density = 1000, thickness = 1e-3;  // kg/m^3, m
  double a = 1600, b = 1.5;                 // m^2/s^2, 1
  // [law]
  std::string pair = "marder", cutoff = "fermi", angle = "marder";
  std::string three_body_weight = "pair";  // pair | all_bonds (bond_law.hpp)
  double three_body_residual = 0;          // κ in [0, 1): 0, the paper's law (three_body_residual.hpp)
  std::string failure = "paper";           // paper | freeze: energy-neutral failure (model.hpp)
  double short_width = 0, cutoff_length = 0, cutoff_width = 0;  // m
  // [physics] and their parameters
  bool damping = false;
  DampingKind damping_kind = DampingKind::uniform;
  double beta = 0, damping_onset = 0;  // kg/s, m
  bool irreversible = false;
  double break_widths = 10;
  bool toughening = false;
  double toughening_trigger = 0, toughening_cutoff = 0;  // m
  long long toughening_every = 10;
  // [loading]
  std::string kind = "stretch";  // stretch | wave
  double stretch_x = 1, stretch_y = 1;
  double ramp_time = 0;    // s: 0, pre-stretched; > 0, the clamped rows move from ramp_from_y to stretch_y
  double ramp_from_y = 0;  // λy at t = 0 when ramp_time > 0
  // [boundary]
  long long clamp_rows = 0, clamp_columns = 0;
  bool periodic_x = false, periodic_y = false;
  // [crack]
  double seed_length = 0, tip_kick = 0;  // m, m/s
  double path_cutoff_ratio = 1;          // the bulk's cut-off over the crack path's (law.cutoff_length): a weak plane
  double drive_speed = 0, drive_length = 0;  // m/s (lab), m (reference): the driven seed (crack_drive.hpp); 0: off
  // [pulse]
  std::string pulse_kind = "longitudinal", pulse_direction = "x";
  double pulse_amplitude = 0, pulse_width = 0, pulse_position = 0.5;  // m, m, fraction
  // [initial]
  double noise = 0;  // m/s
  // [integrator]
  dynamics::IntegratorKind integrator = dynamics::IntegratorKind::verlet;
  double dt = 0;  // s; 0 = auto
  double safety = 0.5;
  bool allow_unstable = false;
  // [stop]
  double t_max = 0;
  long long max_steps = 1000000000;
  double tip_margin = 0;  // m
  // [output]
  double frame_interval = 0;  // s; 0: only the first and last frames
  long long observe_every = 20;
  std::vector<std::string> frames;  // the datasets of every frame (rubber/frames' rows), position among them
  double speed_window = 0;          // s
  int threads = 1;                  // not a scene key: --threads
};

// Reads the scene for this mesh; UsageError naming the key for a bad value: out of its range, beyond
// core/physical_limits.hpp, or a length that does not fit on the sheet (a crack seed longer than it).
RubberScene read_rubber_scene(Scene& scene, const mesh::NodeMesh& mesh);
// The keys a scene for a run must give itself: loading.kind.
void require_run_keys(const Scene& scene);

struct RubberSetup {
  RubberScene scene;
  BondLaw law;
  double spacing = 0, node_mass = 0, rho = 0;                 // m, kg, kg/m^2 (areal)
  Eigen::Matrix2d F = Eigen::Matrix2d::Identity();            // far-field deformation
  double family_length[3] = {0, 0, 0};                        // m: bond lengths of the three families at F
  double family_angle[3] = {0, 0, 0};                         // degrees, reference
  double omega_max = 0, dt_bound = 0, dt = 0;                 // rad/s, s, s
  double omega_far = 0, omega_relaxed = 0, omega_cutoff = 0;  // rad/s: the three states probed
  mr::Speeds mr_x, mr_y;                                      // Mooney-Rivlin lab speeds along x and y at F
  LatticeSpeeds lattice_x, lattice_y;                         // the lattice's own at F, with this law
  std::vector<std::string> warnings;
  // Derived values for /parameters ("derived.*").
  std::vector<std::pair<std::string, std::string>> derived() const;
};

// Builds the law and checks the scene against the mesh: UsageError for a time step above the
// stability bound (unless integrator.allow_unstable), with the bound in the message.
RubberSetup prepare_rubber(const RubberScene& scene, const mesh::NodeMesh& mesh);

// The far-field checks alone (used by prepare_rubber; exposed for tests): bond families shorter than
// Δ + u_s (not Mooney-Rivlin), and a cut-off fewer than 15 widths above the longest far-field bond
// (rubber-lattice-validation.md §D.1), each warning naming its numbers.
std::vector<std::string> far_field_warnings(const RubberSetup& setup);

}  // namespace frac::rubber
