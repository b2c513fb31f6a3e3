// Ctrl-C (SIGINT) and SIGTERM for long runs: the first signal only raises a flag.
// `simulate` asks for it after every step (DeploymentOptions::stop_requested): the integration
// stops there, the outputs computed so far are written to the result file marked incomplete (root
// attributes complete = 0, stopped_at_s; fullorder/result_stream.hpp), and the command ends with
// one line, "interrupted at t = … s; wrote the N output samples computed to FILE, marked
// incomplete …", and kExitInterrupted. `rom eval` asks for it between the blocks of its result
// file (cli/rom_eval_output.hpp): the file ends with the blocks written, marked the same way, and
// the command ends with the same kind of line. Every other command sees the flag at its next
// progress report (cli/progress.hpp), which throws Interrupted, so the stack unwinds as for any
// error — result files still under their temporary names are removed by their writers, nothing
// half-written keeps the final name — and main() prints "interrupted …; no result written".
// Either way the exit code is 128 + SIGINT, the shell's convention. A second signal ends the
// process at once (the default action): the final name then keeps what it held before.
#pragma once

#include <string>

#include "common/error.hpp"

namespace mastrom::cli {

/// Exit code of an interrupted command: 128 + SIGINT, as a shell reports a process ended by Ctrl-C.
inline constexpr int kExitInterrupted = 130;

/// A run stopped by SIGINT or SIGTERM; what() is the whole one-line message.
class Interrupted : public Error {
public:
  using Error::Error;
};

/// Install the handlers (once, in main). Not under an MPI launcher with more than one rank: there
/// the launcher forwards the signal to every rank and ends the job, and one rank unwinding alone
/// would leave the others waiting in a collective call.
void installInterruptHandlers();

/// True once SIGINT or SIGTERM has arrived.
bool interruptRequested();

}  // namespace mastrom::cli
