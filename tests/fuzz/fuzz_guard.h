// fuzz_guard.h — what makes a crash or a hang in one scene of a long run reproducible: the
// scene's recipe line, printed by a signal handler (or the sanitizers' death callback) or by a
// watchdog thread when one scene runs too long; and the library's stderr chatter kept quiet.
#pragma once
#include <string>

namespace btgpu::fuzz {

// Once per process: handlers for SIGSEGV/SIGABRT/SIGFPE/SIGBUS/SIGILL (under ASan/UBSan their
// death callback instead, so their report stays intact) and a watchdog that aborts a scene
// running longer than timeoutSeconds.
void installGuards(double timeoutSeconds);
// The text printed if the process dies or hangs from now until sceneDone().
void guardScene(const std::string& text);
void sceneDone();
// Our own messages, on the real stderr even while QuietStderr is in effect.
void printToStderr(const std::string& text);

// While alive, file descriptor 2 goes to /dev/null (btgpu says each fallback and device on
// stderr, once per world: hundreds of lines in a run). Off under the sanitizers, whose reports
// go to stderr.
class QuietStderr {
public:
    explicit QuietStderr(bool quiet);
    ~QuietStderr();
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    int m_saved = -1;
};

// True when built with -fsanitize=address (BTGPU_SANITIZE).
bool sanitized();

}  // namespace btgpu::fuzz
