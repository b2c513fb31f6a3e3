// Mode tracking between the samples of a ROM database (docs/theory.md §4.3–4.4 (a), (b)): which
// mode of a sample is which mode of the reference sample, with what sign, and the orthogonal
// alignment of the whole mode set.
//
//  * MAC in the reference mass inner product, MAC_ij = (φ_iᵀMψ_j)² / ((φ_iᵀMφ_i)(ψ_jᵀMψ_j));
//  * assignment: the one-to-one matching of reference modes to sample modes with the largest total
//    MAC (Hungarian algorithm, Kuhn 1955 / Munkres 1957, in the O(n²m) potentials form) — greedy
//    matching can pair two modes wrongly when two shapes swap between samples;
//  * sign: that of φ_sᵀ M φ_ref of the matched pair;
//  * alignment (orthogonal Procrustes in the mass inner product, as in Amsallem & Farhat 2008 and
//    libROM's manifold_interp): Q = U Vᵀ from the SVD Φ_sᵀ M Φ_ref = U Σ Vᵀ minimises
//    ‖Φ_s Q − Φ_ref‖_M over orthogonal Q.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

namespace mastrom::rom {

struct ModeTracking {
  std::vector<int> tracking;  ///< reference mode j ↔ sample mode tracking[j]
  std::vector<int> sign;      ///< ±1: sample mode tracking[j] times sign[j] ≈ reference mode j
  Eigen::VectorXd mac;        ///< MAC of each matched pair (per reference mode)
  Eigen::MatrixXd alignment;  ///< Q (k_s × k_ref): Φ_s Q ≈ Φ_ref
};

/// One-to-one assignment maximising the total weight: row r (of n ≤ m rows) gets column
/// result[r]. Throws InputError when rows > columns or a weight is not finite.
std::vector<int> maximumWeightAssignment(const Eigen::MatrixXd& weight);

/// Track the sample's modes (n × k_s, k_s ≥ k_ref) against the reference's (n × k_ref) in the
/// mass inner product of `mass` (the reference's M). Throws InputError on a size mismatch.
ModeTracking trackModes(const Eigen::MatrixXd& phi_sample, const Eigen::MatrixXd& phi_reference,
                        const Eigen::SparseMatrix<double>& mass);

}  // namespace mastrom::rom
