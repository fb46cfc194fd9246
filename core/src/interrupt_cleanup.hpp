// Folders to remove when the process is interrupted (see
// touchcloud/interrupt_cleanup.hpp). Private to the core.
#pragma once

#include <filesystem>
#include <mutex>

namespace touchcloud::interrupt {

void remove_on_interrupt(const std::filesystem::path& folder);
void forget(const std::filesystem::path& folder);
// Held while outputs move into place, so an interrupt waits for the move
// to finish rather than remove files half way.
std::unique_lock<std::mutex> hold_off();

}  // namespace touchcloud::interrupt
