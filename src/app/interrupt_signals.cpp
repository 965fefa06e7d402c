#include "app/interrupt_signals.h"

#include <csignal>

namespace pt {
namespace {

volatile std::sig_atomic_t caught = 0;
struct sigaction previousInt, previousTerm;

extern "C" void onSignal(int signal) {
    if (caught == 0) caught = signal;
    // SA_RESETHAND restored the default action for this signal; do the same for the other so a
    // second Ctrl-C or kill ends a render that is stuck.
    std::signal(signal == SIGINT ? SIGTERM : SIGINT, SIG_DFL);
}

} // namespace

InterruptSignals::InterruptSignals() {
    caught = 0;
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND | SA_RESTART;
    sigaction(SIGINT, &action, &previousInt);
    sigaction(SIGTERM, &action, &previousTerm);
}

InterruptSignals::~InterruptSignals() {
    sigaction(SIGINT, &previousInt, nullptr);
    sigaction(SIGTERM, &previousTerm, nullptr);
}

int InterruptSignals::received() { return caught; }

} // namespace pt
