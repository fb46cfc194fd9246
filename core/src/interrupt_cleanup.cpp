#include "touchcloud/interrupt_cleanup.hpp"

#include <pthread.h>
#include <cstdlib>
#include <signal.h>

#include <iostream>
#include <set>
#include <thread>

#include "interrupt_cleanup.hpp"

namespace fs = std::filesystem;

namespace touchcloud {

namespace {

std::mutex& folders_mutex() {
  static std::mutex m;
  return m;
}
std::set<fs::path>& folders() {
  static std::set<fs::path> f;
  return f;
}
std::string& message() {
  static std::string m;
  return m;
}
std::function<void()>& stop_handler() {
  static std::function<void()> f;
  return f;
}

sigset_t handled_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, s);
  return set;
}

[[noreturn]] void wait_for_signal(sigset_t set) {
  int signal_number = 0;
  for (;;) {
    while (sigwait(&set, &signal_number) != 0) {
    }
    std::function<void()> stop;
    {
      std::lock_guard<std::mutex> lock(folders_mutex());
      stop.swap(stop_handler());
    }
    if (!stop) break;
    stop();
  }
  {
    std::lock_guard<std::mutex> lock(folders_mutex());
    std::error_code ec;
    for (const auto& f : folders()) fs::remove_all(f, ec);
    if (!message().empty()) std::cerr << message() << "\n" << std::flush;
  }
  // End as the signal would have: default action, delivered to this thread.
  ::signal(signal_number, SIG_DFL);
  sigset_t one;
  sigemptyset(&one);
  sigaddset(&one, signal_number);
  pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
  ::raise(signal_number);
  std::_Exit(128 + signal_number);
}

}  // namespace

void clean_up_on_interrupt() {
  static std::once_flag once;
  std::call_once(once, [] {
    sigset_t set = handled_signals();
    // A signal the parent set to be ignored (nohup, background jobs) stays so.
    for (int s : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction current {};
      if (sigaction(s, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) sigdelset(&set, s);
    }
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
    std::thread(wait_for_signal, set).detach();
  });
}

void say_on_interrupt(std::string text) {
  std::lock_guard<std::mutex> lock(folders_mutex());
  message() = std::move(text);
}

void stop_on_interrupt(std::function<void()> stop) {
  std::lock_guard<std::mutex> lock(folders_mutex());
  stop_handler() = std::move(stop);
}

namespace interrupt {

void remove_on_interrupt(const fs::path& folder) {
  std::lock_guard<std::mutex> lock(folders_mutex());
  folders().insert(folder);
}

void forget(const fs::path& folder) {
  std::lock_guard<std::mutex> lock(folders_mutex());
  folders().erase(folder);
}

std::unique_lock<std::mutex> hold_off() { return std::unique_lock<std::mutex>(folders_mutex()); }

}  // namespace interrupt

}  // namespace touchcloud
