#pragma once
// The host's request that running evaluations stop early. Nodes of SDK 1.x plugins poll it through
// the eval suite's cancelled() (docs/design/sdk-1.0.md, section 1.3) and return MG_ERR_CANCELLED;
// the node's evaluation then fails with "stopped: ... cancelled". One flag for the process: a
// signal handler may set it (a lock-free atomic store). Today nothing in the CLI sets it yet; the
// sweep's Ctrl-C still lets started cases finish.
namespace mechgraph {

void request_cancellation() noexcept;
void clear_cancellation() noexcept;
bool cancellation_requested() noexcept;

}  // namespace mechgraph
