// The assembled rigid–flexible multibody system (docs/theory.md §5; [LW24] eqs. 42–46):
//   M q̈ + Φ_qᵀλ = Q(q, q̇, t),   Φ(q, t) = 0,
//   Q = s·(Q_gravity + Q_loads(q, t)) − F_elastic(q) − F_damping(q, q̇)   (load scale s, default 1)
// with rigid modules in natural coordinates (fullorder/ncf_body.hpp), ANCF shell elements
// (fullorder/shell_element.hpp), constraint blocks (fullorder/constraint.hpp) and applied loads
// (fullorder/applied_loads.hpp).
//
// DOF map: all bodies' 12-blocks first (body b at 12·b), then all shell nodes' 9-blocks
// (node k at 12·n_bodies + 9·k). Multipliers: the constraint blocks in the order they were added;
// every rigid body's six internal constraints are added automatically by addRigidBody().
//
// Life cycle: add bodies (all of them first), then meshes, constraints and loads; finalize() builds
// the constant mass matrix and the sparsity patterns, after which nothing can be added.
//
// Iteration matrix (one function serves statics, modes and every integrator; the coefficients are
// fullorder/dae_system.hpp's IterationCoefficients):
//   H = [ c_m M + c_d C_t + c_k (K_t + K_d + (Φ_qᵀλ)_q − s K_load) ,  σ Φ_qᵀ ]
//       [ σ Φ_q                                                       ,  0     ]
// K_t = ∂F_elastic/∂q, C_t = ∂F_damping/∂q̇, K_d = ∂F_damping/∂q, K_load = ∂Q_loads/∂q, σ = the
// constraint scale (Bottasso, Dopico & Trainelli 2008), s = the load scale. λ passed in is always
// the physical multiplier. The pattern of H (all blocks, the diagonal included) is computed once in
// finalize(); for every element/constraint/load local entry its position in H's CSC value array is
// stored, so re-assembly zeroes the values and scatters — no allocation, no search, no sort.
//
// The class implements the integrator's DaeSystem interface (fullorder/dae_system.hpp) by
// forwarding to the const methods below (load scale 1).
//
// Gravity: a uniform field g has the exact coordinates q_g (g in every position slot — r_i, r_j of
// a body, r of a node — zero in every direction/slope slot), because A(c) q_g = g and S q_g = g
// (partition of unity). Hence Q_gravity = ∫ρ Sᵀg = M q_g exactly, the potential is V_g = −q_gᵀ M q,
// and the total mass is q_gᵀ M q_g / |g|².
//
// Not thread-safe: evaluation uses internal scratch buffers. Use one system per thread. (Inside,
// the element forces may run on several threads: setThreadCount.)
//
// The elements of one mesh share one shape-function table (ShellShapeTable): they all have the same
// a × b parameter rectangle. Their reference metrics differ only by a rigid rotation and are kept
// per element (16 doubles per point), which keeps the code valid for any mesh.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/StdVector>
#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "fullorder/applied_loads.hpp"
#include "fullorder/constraint.hpp"
#include "fullorder/dae_system.hpp"
#include "fullorder/ncf_body.hpp"
#include "fullorder/shell_element.hpp"
#include "fullorder/shell_force_batch.hpp"
#include "fullorder/shell_mesh.hpp"

namespace mastrom::fullorder {

class MultibodySystem final : public DaeSystem {
public:
  using ConstVec = Eigen::Ref<const Eigen::VectorXd>;

  MultibodySystem() = default;
  MultibodySystem(MultibodySystem&&) = default;
  MultibodySystem& operator=(MultibodySystem&&) = default;

  // ---------------------------------------------------------------- building
  /// Add a rigid body with its reference coordinates; also adds its six internal constraints.
  /// Bodies must all be added before the first mesh. @return the body index.
  int addRigidBody(const RigidModule& body, const Vec12& reference);
  /// Add every node and element of `mesh`. @return the global id of the mesh's first node
  /// (mesh node k becomes global node first + k).
  int addShellMesh(const ShellMesh& mesh, const ShellSection& section, int gauss_order = 5);
  /// @return the offset of the block's multipliers in λ.
  int addConstraint(std::unique_ptr<ConstraintBlock> block);
  void addLoad(std::unique_ptr<AppliedLoad> load);
  void setGravity(const Eigen::Vector3d& gravity_m_s2);
  /// Build the mass matrix and the sparsity patterns. Required before any evaluation.
  void finalize();
  bool isFinalized() const { return finalized_; }

  // ---------------------------------------------------------------- layout
  int dofCount() const override { return 12 * bodyCount() + 9 * nodeCount(); }
  int constraintCount() const override { return n_constraints_; }
  int bodyCount() const { return static_cast<int>(bodies_.size()); }
  int nodeCount() const { return static_cast<int>(node_reference_.size()); }
  int elementCount() const { return static_cast<int>(elements_.size()); }
  int bodyDofOffset(int body) const { return 12 * body; }
  int nodeDofOffset(int node) const { return 12 * bodyCount() + 9 * node; }
  const RigidModule& body(int b) const { return bodies_[static_cast<size_t>(b)]; }
  const Vec9& nodeReference(int node) const { return node_reference_[static_cast<size_t>(node)]; }
  const Eigen::Vector3d& nodeNormal(int node) const {
    return node_normal_[static_cast<size_t>(node)];
  }
  const ShellElement& element(int e) const { return elements_[static_cast<size_t>(e)]; }
  const std::array<int, 36>& elementDofs(int e) const {
    return element_dofs_[static_cast<size_t>(e)];
  }
  int constraintBlockCount() const { return static_cast<int>(constraints_.size()); }
  const ConstraintBlock& constraintBlock(int k) const {
    return *constraints_[static_cast<size_t>(k)];
  }
  int constraintBlockOffset(int k) const { return constraint_offset_[static_cast<size_t>(k)]; }
  /// The reference configuration q₀ (bodies' reference coordinates, nodes' e₀).
  const Eigen::VectorXd& referenceCoordinates() const { return q_reference_; }
  const Eigen::Vector3d& gravity() const { return gravity_; }

  // ---------------------------------------------------------------- mass, forces, energies
  /// Constant mass matrix (ndof × ndof).
  const SparseMatrix& massMatrix() const override { return mass_; }
  /// f = s·(Q_gravity + Q_loads) − F_elastic − F_damping. f is resized if needed.
  void forces(const ConstVec& q, const ConstVec& qdot, double t, Eigen::VectorXd& f,
              double load_scale = 1.0) const;
  /// forces(q, q̇, t, f), constraints(q, t, phi) and constraintJacobian(q, t, g) at once, with the
  /// constraints evaluated on one thread while the element forces run on the others (results
  /// bit-identical to the three calls).
  /// `side_work` (optional) runs first on the calling thread, before f, phi or g is written; it is
  /// taken to be long (an index-1 recovery), so the other threads take all element chunks.
  void forcesAndConstraints(const ConstVec& q, const ConstVec& qdot, double t, Eigen::VectorXd& f,
                            Eigen::VectorXd& phi, SparseMatrix& g,
                            const std::function<void()>* side_work = nullptr) const;
  /// The same three results computed entirely on the calling thread with the scratch of `slot`:
  /// slot 0 is the scratch every other call uses, slot 1 a second set, so two threads may evaluate
  /// two states at once (slot 1 on one, slot 0 on the other — and no other call meanwhile). Equal
  /// bit for bit to forcesAndConstraints() (the pipelined time step,
  /// EliminatedSystem::evaluatePair).
  void forcesAndConstraintsInSlot(int slot, const ConstVec& q, const ConstVec& qdot, double t,
                                  Eigen::VectorXd& f, Eigen::VectorXd& phi, SparseMatrix& g) const;
  /// f += Φ_qᵀ λ (the constraint forces enter the equations of motion with this sign).
  void addConstraintForces(const ConstVec& q, const ConstVec& lambda, double t,
                           Eigen::VectorXd& f) const;
  /// Threads for the element forces (default 1; a build without OpenMP uses one whatever is set).
  /// Results do not depend on it, bit for bit. Use 1 when other processes share the cores (MPI
  /// ranks): OpenMP's waiting helper threads spin.
  void setThreadCount(int threads);
  int threadCount() const { return threads_; }
  /// Gravity's generalized force M q_g (constant).
  const Eigen::VectorXd& gravityForce() const { return gravity_force_; }

  double kineticEnergy(const ConstVec& qdot) const;
  double strainEnergy(const ConstVec& q) const;
  /// V_g = −q_gᵀ M q (zero at the origin-level reference of each mass point).
  double gravityPotential(const ConstVec& q) const;
  /// Power dissipated by Kelvin–Voigt damping, q̇ᵀ F_damping ≥ 0.
  double dampingPower(const ConstVec& q, const ConstVec& qdot) const;
  /// Total mass, from the mass matrix (exact for the interpolated shell geometry).
  double totalMass() const { return total_mass_; }

  // ---------------------------------------------------------------- constraints
  void constraints(const ConstVec& q, double t, Eigen::VectorXd& phi) const;
  /// Φ_q with its fixed pattern; G is (re)shaped on first use, then only its values change.
  void constraintJacobian(const ConstVec& q, double t, SparseMatrix& g) const;
  void constraintTimeDerivative(const ConstVec& q, double t, Eigen::VectorXd& phi_t) const;
  void constraintSecondTimeDerivative(const ConstVec& q, double t, Eigen::VectorXd& phi_tt) const;
  /// γ_v = (Φ_q q̇)_q q̇ + 2Φ_qt q̇, so that Φ_q q̈ = −(γ_v + Φ_tt) (consistent accelerations,
  /// [LW24] eq. 45).
  void constraintVelocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                              Eigen::VectorXd& gamma) const;

  // ---------------------------------------------------------------- iteration matrix
  /// Assemble H (see header comment) into `h`: if `h` does not have this system's pattern it is
  /// replaced by a copy of it first; afterwards only values are written.
  void assembleIterationMatrix(const ConstVec& q, const ConstVec& qdot, const ConstVec& lambda,
                               double t, const IterationCoefficients& coeffs, SparseMatrix& h,
                               double load_scale = 1.0) const;
  /// Same, and the forces f of forces(q, q̇, t, f, load_scale) from the same element calls.
  void assembleForcesAndIterationMatrix(const ConstVec& q, const ConstVec& qdot,
                                        const ConstVec& lambda, double t,
                                        const IterationCoefficients& coeffs, Eigen::VectorXd& f,
                                        SparseMatrix& h, double load_scale = 1.0) const;
  /// The pattern of H ((ndof + ncon)², all values zero): for a one-time analyzePattern().
  const SparseMatrix& iterationMatrixPattern() const { return h_pattern_; }

  // ---------------------------------------------------------------- DaeSystem (load scale 1)
  void forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
              Eigen::VectorXd& q_force) override;
  void constraints(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi) override;
  void constraintJacobian(const Eigen::VectorXd& q, double t, SparseMatrix& jac) override;
  void evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                Eigen::VectorXd& q_force, Eigen::VectorXd& phi, SparseMatrix& jac,
                const std::function<void()>* side_work = nullptr) override;
  /// −Φ_t.
  void velocityConstraintRhs(const Eigen::VectorXd& q, double t, Eigen::VectorXd& rhs) override;
  /// −(γ_v + Φ_tt).
  void accelerationConstraintRhs(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                                 Eigen::VectorXd& rhs) override;
  void iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                       const Eigen::VectorXd& lambda, double t, const IterationCoefficients& coeffs,
                       SparseMatrix& h) override;
  /// Present when every constraint block declares its rows under a turn about Z
  /// (ConstraintBlock::rotatingRowTriples), at most one block is time-dependent and no load has a
  /// stiffness: every coordinate block (r_i, r_j, u, v of a body; r, r_x, r_y of a node) is a
  /// 3-vector and the elastic energy is frame-invariant, so H is equivariant. Set by finalize().
  const RotationSymmetry* rotationSymmetry() const override {
    return rotation_symmetry_.triple_starts.empty() ? nullptr : &rotation_symmetry_;
  }
  /// frameAngle(t) of the time-dependent block (the drive), 0 without one.
  double rotationAngle(double t) const override;

  // ---------------------------------------------------------------- rigid-motion helpers
  /// Every 3-block of q multiplied by `rotation` (a rigid rotation about the global origin).
  Eigen::VectorXd rotated(const ConstVec& q, const Eigen::Matrix3d& rotation) const;
  /// The coordinates of a uniform field v: v in every position slot, zero in direction slots.
  Eigen::VectorXd uniformField(const Eigen::Vector3d& v) const;

private:
  // The phases of finalize().
  void checkDofRanges() const;
  void buildForceBatches();
  void assembleReferenceAndMass();
  void buildSparsityPatterns(std::vector<BoolMatrix>& jac_struct,
                             std::vector<BoolMatrix>& hess_struct);
  void buildScatterMaps(const std::vector<BoolMatrix>& jac_struct,
                        const std::vector<BoolMatrix>& hess_struct);
  void detectRotationSymmetry();
  /// f −= elastic + damping forces of all elements (see setThreadCount).
  void subtractElementForces(const double* q, const double* qdot, double* f) const;
  /// Every element chunk into chunk_lanes_, on up to threads_ threads; `side_work` (optional) runs
  /// on the calling thread meanwhile, which then takes fewer chunks (none if `heavy_side_work`).
  /// Rethrows the first failure after all have run.
  void evaluateElementChunks(const double* q, const double* qdot,
                             const std::function<void()>* side_work, bool heavy_side_work) const;
  /// f −= the chunk results `lanes` (kChunkValues per chunk), in chunk order.
  void subtractChunkResults(const double* lanes, double* f) const;
  struct BlockScratch {
    Eigen::VectorXd q, qdot, lambda, out;
    Eigen::MatrixXd jac, hess;
  };
  /// f += load_scale · (applied loads' forces).
  void addLoadForces(std::vector<BlockScratch>& scratch, const ConstVec& q, double t,
                     double load_scale, Eigen::VectorXd& f) const;
  void constraintsWith(std::vector<BlockScratch>& scratch, const ConstVec& q, double t,
                       Eigen::VectorXd& phi) const;
  void constraintJacobianWith(std::vector<BlockScratch>& scratch, const ConstVec& q, double t,
                              SparseMatrix& g) const;
  /// Local entry (flat column-major index in the dense local block) → position in a CSC array.
  struct Scatter {
    std::vector<int> local;
    std::vector<int> position;
  };

  void requireFinalized(const char* what) const;
  void gather(const ConstraintBlock& block, const ConstVec& q, Eigen::VectorXd& out) const;
  void assemble(const ConstVec& q, const ConstVec& qdot, const ConstVec& lambda, double t,
                const IterationCoefficients& coeffs, double load_scale, Eigen::VectorXd* f,
                SparseMatrix& h) const;

  bool finalized_ = false;
  std::vector<RigidModule> bodies_;
  std::vector<Vec12> body_reference_;
  std::vector<Vec9> node_reference_;
  std::vector<Eigen::Vector3d> node_normal_;
  std::vector<ShellElement> elements_;
  std::vector<std::array<int, 36>> element_dofs_;
  std::vector<bool> element_damped_;
  std::vector<std::unique_ptr<ConstraintBlock>> constraints_;
  std::vector<int> constraint_offset_;
  int n_constraints_ = 0;
  std::vector<std::unique_ptr<AppliedLoad>> loads_;
  Eigen::Vector3d gravity_ = Eigen::Vector3d::Zero();

  // Built by finalize().
  Eigen::VectorXd q_reference_;
  SparseMatrix mass_;
  Eigen::VectorXd gravity_force_;
  double total_mass_ = 0.0;
  SparseMatrix h_pattern_;
  /// Internal forces of the elements, batched by shape table (the time-stepping hot path).
  std::vector<ShellForceBatch> force_batches_;
  struct ChunkRef {
    int batch, chunk;
  };
  std::vector<ChunkRef> chunk_refs_;         ///< every chunk of every batch, in order
  mutable std::vector<double> chunk_lanes_;  ///< their results (kChunkValues each)
  int threads_ = 1;
  std::vector<int> mass_in_h_;                  ///< position in H of every stored entry of M
  std::vector<std::vector<int>> element_in_h_;  ///< 36×36 positions per element (column-major)
  std::vector<Scatter> jac_in_h_, jact_in_h_, hess_in_h_, jac_in_g_;
  std::vector<Scatter> load_in_h_;
  SparseMatrix g_pattern_;
  RotationSymmetry rotation_symmetry_;  ///< empty: none
  int frame_block_ = -1;                ///< the time-dependent block that sets rotationAngle()
  mutable std::vector<BlockScratch> block_scratch_, load_scratch_;
  /// The second scratch set of forcesAndConstraintsInSlot(1, …).
  struct SpareScratch {
    std::vector<double> chunk_lanes;
    std::vector<BlockScratch> blocks, loads;
  };
  mutable SpareScratch spare_;
  /// The element tangents of an assembly, formed on the threads allowed before they are added in
  /// element order (assemble()).
  mutable std::vector<Mat36, Eigen::aligned_allocator<Mat36>> element_tangents_;
};

}  // namespace mastrom::fullorder
