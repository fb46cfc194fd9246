// SIGINT, SIGTERM and SIGHUP end a run without leaving its staging folder
// behind. A program that runs pipelines (the CLI) calls this once, first
// thing in main(), before any thread starts: the signals are then blocked in
// every thread and one thread waits for them, removes the staging folders of
// the runs in progress and ends the process with the same signal.
#pragma once

namespace touchcloud {

void clean_up_on_interrupt();

}  // namespace touchcloud
