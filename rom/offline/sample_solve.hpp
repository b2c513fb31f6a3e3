// One database sample's offline work (docs/theory.md §4.3): the configuration at the sample's
// parameters → the locked mast's modes (rom/offline/locked_modal_solve.hpp) → a canonical or aligned basis
// of every degenerate cluster → the modal model (rom/model/modal_extraction.hpp). The reference sample's
// clusters are made canonical; every other sample's are rotated to match the reference's modes, so
// that MAC tracking (rom/offline/mode_tracking.hpp) sees the same shapes.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "common/config.hpp"
#include "common/kinds.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// Extra modes solved beyond the stored count, so that a degenerate pair or triplet cut by the
/// window's upper edge is still aligned as a whole.
constexpr int kExtraModes = 2;

/// One sample's modal solve, with what tracking needs (Φ and the mass matrix stay on this rank).
struct SampleSolution {
  ModalModel modal;
  Eigen::MatrixXd modes;  ///< Φ with the extra modes (columns beyond the stored count)
  Eigen::SparseMatrix<double> mass;
  double assembly_s = 0.0, eigensolve_s = 0.0, extraction_s = 0.0;
};

/// Solve sample `index` at `point` (one value per axis of `axes`) over the base configuration
/// for `modes` modes (plus kExtraModes). `reference` = nullptr for the reference sample itself (its degenerate eigenspaces
/// are made canonical); otherwise they are aligned to the reference's modes. Errors name the
/// sample and its parameters.
/// `stresses`: also the interfaces' modal stresses (rom/model/modal_stress_extraction.hpp).
SampleSolution solveSample(const Config& base, const std::vector<ParameterAxis>& axes,
                           const std::vector<double>& point, int modes, EigenBackendKind backend,
                           int index, const SampleSolution* reference, bool stresses = true);

/// The modes rigidly rotated by `angle_rad` about Z (samples locked at different angles θ₀ are
/// compared in the reference's frame; see sample_solve.cpp).
Eigen::MatrixXd rotateModes(const Eigen::MatrixXd& phi, double angle_rad);

/// "key=value, …" of a parameter point, for messages.
std::string describePoint(const std::vector<ParameterAxis>& axes, const std::vector<double>& p);

}  // namespace mastrom::rom
