// The modal ROM of one configuration, solved directly at that configuration's own parameters
// (docs/theory.md §4.1), with no database and no interpolation: locked mast at modes.angle_deg →
// static equilibrium and linearisation (modes/linearize.hpp) → constrained eigenproblem with the
// configuration's backend → ModalModel (rom/model/modal_extraction.hpp). This is what `mastrom study`
// runs as "the ROM" of a case: its error against the full order is then the modal truncation and
// linearisation error alone (docs/theory.md §4.1), not an interpolation error on top (that is
// measured by `rom build`'s leave-one-out estimate and by `mastrom validate`).
//
// Degenerate clusters (the y/z bending pairs of the symmetric mast) are kept whole: when the
// requested count cuts a cluster, the model takes the rest of it too, because the split of a cut
// cluster is an arbitrary basis choice of the solver and would make the response depend on it. A
// whole cluster's contribution Σ φφᵀ does not depend on the basis.
#pragma once

#include "common/config.hpp"
#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

/// The modal model of `config` with at least `modes` modes (0 = config.modes.count; more only to
/// complete a degenerate cluster, modes/mode_basis.hpp). With the SLEPc backend a modes::SlepcSession must be alive.
/// Throws InputError when more modes are requested than the model has, NumericalError when the
/// equilibrium or the eigen-solve fails.
ModalModel directModalModel(const Config& config, int modes = 0);

/// Index of the first mode the drive excites (|Γ_k| ≥ 1e-3 max |Γ|): the first in-plane bending
/// mode, whose frequency and decay time the study table reports. −1 when no mode is excited.
int firstExcitedMode(const ModalModel& model);

}  // namespace mastrom::rom
