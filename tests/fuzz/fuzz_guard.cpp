// fuzz_guard.cpp — crash and hang reporting for the fuzz run. The handler only calls write()
// on a buffer filled before the scene started (async-signal-safe), then dies by the same signal.
#include "fuzz_guard.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <thread>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__)
#define BTGPU_FUZZ_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BTGPU_FUZZ_ASAN 1
#endif
#endif
#ifdef BTGPU_FUZZ_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace btgpu::fuzz {

namespace {

char g_text[16384];
std::atomic<size_t> g_length{0};
std::atomic<long long> g_sceneStart{0};  // steady-clock ms, 0 between scenes
int g_errFd = 2;

long long nowMs()
{
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

void writeAll(const char* s, size_t n)
{
    while (n > 0) {
        ssize_t w = ::write(g_errFd, s, n);
        if (w <= 0) return;
        s += w;
        n -= size_t(w);
    }
}

void writeScene(const char* why)
{
    writeAll("\n*** btgpu fuzz: ", 17);
    writeAll(why, std::strlen(why));
    writeAll(" in this scene:\n", 16);
    if (g_sceneStart.load() == 0) {
        writeAll("(between scenes)\n", 17);
        return;
    }
    writeAll(g_text, g_length.load());
    writeAll("\n", 1);
}

void onSignal(int sig)
{
    const char* name = sig == SIGSEGV ? "SIGSEGV" : sig == SIGABRT ? "SIGABRT" : sig == SIGFPE ? "SIGFPE"
                     : sig == SIGBUS ? "SIGBUS" : "SIGILL";
    writeScene(name);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

#ifdef BTGPU_FUZZ_ASAN
// ASan's death callback prints the scene after an ASan report. GCC links UBSan as a runtime of
// its own, which calls no callback of ASan's and resets SIGABRT before aborting: for UB the
// seed line printed before each scene (sanitized builds only) names the scene.
extern "C" const char* __ubsan_default_options() { return "print_stacktrace=1"; }
void onDeath() { writeScene("sanitizer report (above)"); }
#endif

bool sanitized()
{
#ifdef BTGPU_FUZZ_ASAN
    return true;
#else
    return false;
#endif
}

void installGuards(double timeoutSeconds)
{
    static bool done = false;
    if (done) return;
    done = true;
    g_errFd = ::dup(2);
    if (g_errFd < 0) g_errFd = 2;
#ifdef BTGPU_FUZZ_ASAN
    // ASan reports faults itself (its handler must stay); it leaves SIGABRT alone.
    __sanitizer_set_death_callback(onDeath);
    std::signal(SIGABRT, onSignal);
#else
    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL}) std::signal(sig, onSignal);
#endif
    const long long limitMs = (long long)(timeoutSeconds * 1000.0);
    std::thread([limitMs] {
        for (;;) {
            std::this_thread::sleep_for(std::chrono::milliseconds(500));
            long long start = g_sceneStart.load();
            if (start != 0 && nowMs() - start > limitMs) {
                writeScene("hang (BTGPU_FUZZ_TIMEOUT seconds passed)");
                std::signal(SIGABRT, SIG_DFL);
                std::abort();
            }
        }
    }).detach();
}

void guardScene(const std::string& text)
{
    size_t n = std::min(text.size(), sizeof(g_text) - 1);
    g_sceneStart.store(0);
    std::memcpy(g_text, text.data(), n);
    g_length.store(n);
    g_sceneStart.store(nowMs());
}

void sceneDone() { g_sceneStart.store(0); }

void printToStderr(const std::string& text) { writeAll(text.data(), text.size()); }

QuietStderr::QuietStderr(bool quiet)
{
    if (!quiet || sanitized()) return;
    int null = ::open("/dev/null", O_WRONLY);
    if (null < 0) return;
    m_saved = ::dup(2);
    ::dup2(null, 2);
    ::close(null);
}

QuietStderr::~QuietStderr()
{
    if (m_saved < 0) return;
    ::dup2(m_saved, 2);
    ::close(m_saved);
}

}  // namespace btgpu::fuzz
