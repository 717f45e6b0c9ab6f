#pragma once
// The failure classes a host reports, one number each: the exit codes of the `mechgraph` program
// (README) and the exit_code column of a sweep's rows, whichever host wrote them.
namespace mechgraph::host {

/// 0 success, 2 bad scene or usage, 3 evaluation error, 4 plugin load error, 5 results could not
/// be written, 6 a plugin-test check failed, 130 stopped by Ctrl-C or SIGTERM (a sweep: its rows
/// so far kept).
enum ExitCode : int { ok = 0, usage_error = 2, evaluation_error = 3, plugin_error = 4, io_error = 5, conformance_failed = 6,
                     interrupted = 130 };

}  // namespace mechgraph::host
