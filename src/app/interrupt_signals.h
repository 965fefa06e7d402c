#pragma once
// SIGINT and SIGTERM during `pt render`: the first asks the render to stop after the pass in
// progress, save its checkpoint and partial image, and exit with 128 + the signal number (130,
// 143); a second one of either ends the process at once (the default action).
namespace pt {

class InterruptSignals {
public:
    InterruptSignals();  // installs the handlers
    ~InterruptSignals(); // restores the previous ones
    InterruptSignals(const InterruptSignals&) = delete;
    InterruptSignals& operator=(const InterruptSignals&) = delete;

    static int received(); // the first signal caught, or 0
};

} // namespace pt
