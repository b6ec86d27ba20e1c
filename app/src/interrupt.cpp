#include "interrupt.hpp"

#include <csignal>

#include "flagsim/core/stop_request.hpp"

namespace flagsim::app {
namespace {

struct sigaction g_previous_int, g_previous_term;

extern "C" void on_signal(int) {
  request_stop();
}

}  // namespace

InterruptGuard::InterruptGuard() {
  clear_stop_request();
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &g_previous_int);
  sigaction(SIGTERM, &action, &g_previous_term);
}

InterruptGuard::~InterruptGuard() {
  sigaction(SIGINT, &g_previous_int, nullptr);
  sigaction(SIGTERM, &g_previous_term, nullptr);
}

bool InterruptGuard::requested() {
  return stop_requested();
}

}  // namespace flagsim::app
