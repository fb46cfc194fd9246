// SIGINT, SIGTERM and SIGHUP end a run without leaving its staging folder
// behind. A program that runs pipelines (the CLI) calls this once, first
// thing in main(), before any thread starts: the signals are then blocked in
// every thread and one thread waits for them, removes the staging folders of
// the runs in progress and ends the process with the same signal.
#pragma once

#include <functional>
#include <string>

namespace touchcloud {

void clean_up_on_interrupt();

// A message printed on stderr when such a signal ends the process (empty:
// none): what the interrupted work leaves behind and how to go on. A batch
// keeps it current as its runs progress.
void say_on_interrupt(std::string message);

// While set, the first such signal calls `stop` instead (a stream then ends
// as a recording's end would end it, writing what it has); a second one
// ends the process as above. Empty: no longer.
void stop_on_interrupt(std::function<void()> stop);

}  // namespace touchcloud
