// Where output.step is unset, the output step a run chooses from its response (docs/theory.md
// §5.4a, rom/model/output_resolution.hpp): the full order from the modes of its mast locked at the
// start configuration, the ROM from its own interpolated modes. Both write the chosen step into
// the configuration, so the resolved configuration stored in the result says what ran, and a
// restart of the same configuration chooses the same step.
#pragma once

#include <optional>

#include "common/config.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/output_resolution.hpp"

namespace mastrom::rom {

/// Modes of the locked mast the full order's choice looks at (more where a cluster is cut).
inline constexpr int kOutputStepModes = 20;

/// The choice for `model`'s response to `config`'s drive (its end time; bytes_per_sample: of the
/// result file, fullorder/run_footprint.hpp). Does not look at output.step.
OutputStepChoice outputStepForModel(const Config& config, const ModalModel& model,
                                    double bytes_per_sample);

/// The choice for the full order of `config`: from the modal model of its mast locked at the
/// drive's start angle θ(0) (rom/offline/direct_modal_model.hpp; with the SLEPc backend a
/// modes::SlepcSession must be alive). Does not look at output.step.
OutputStepChoice fullOrderOutputStep(const Config& config, double bytes_per_sample);

/// Unset output.step with adaptive steps: choose it for the full order — the modal model of
/// `config`'s mast locked at the drive's start angle θ(0) (rom/offline/direct_modal_model.hpp;
/// with the SLEPc backend a modes::SlepcSession must be alive) — and set it in `config`. Returns
/// the choice; empty when output.step is set or the steps are fixed (output.every decides).
std::optional<OutputStepChoice> resolveFullOrderOutputStep(Config& config, double bytes_per_sample);

/// The same for a ROM deployment of `model` (the model is its own response).
std::optional<OutputStepChoice> resolveRomOutputStep(Config& config, const ModalModel& model,
                                                     double bytes_per_sample);

}  // namespace mastrom::rom
