#include "gl_fixture.h"

#include "renderer/core/image_io.h"

#include <execinfo.h>
#include <signal.h>
#include <unistd.h>

namespace {

// A test process that aborts (a heap check in malloc, an assertion in a driver) or crashes prints the stack of the
// thread that did, so a failure seen once in CI says where it came from (the suite once aborted in malloc, rarely,
// in a run that ASan and Valgrind both find clean).
void printStackAndDie(int sig) {
    void* frames[64];
    const int n = backtrace(frames, 64);
    const char header[] = "\n*** fatal signal in the test process; stack (addr2line -e deepgi_tests for the offsets):\n";
    if (write(STDERR_FILENO, header, sizeof(header) - 1) < 0) {}
    backtrace_symbols_fd(frames, n, STDERR_FILENO);
    signal(sig, SIG_DFL);
    raise(sig);
}

#ifndef __SANITIZE_ADDRESS__  // under ASan its own handler reports (with better stacks)
const bool kStackOnFatalSignal = [] {
    void* warm[1];
    backtrace(warm, 1);  // loads libgcc now: a first call inside the handler would malloc, in a process whose heap broke
    for (int sig : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL}) signal(sig, printStackAndDie);
    return true;
}();
#endif

}  // namespace

namespace deepgi::test {

void dumpIfRequested(const std::string& name, const FloatImage& img) {
    if (const char* dir = std::getenv("DEEPGI_TEST_OUT")) writeExr(std::string(dir) + "/" + name + ".exr", img);
}

std::shared_ptr<Scene> cornellScene() {
    using namespace procedural;
    auto s = std::make_shared<Scene>();
    int white = addMaterial(*s, glm::vec3(0.75f));
    int red = addMaterial(*s, glm::vec3(0.75f, 0.1f, 0.1f));
    int green = addMaterial(*s, glm::vec3(0.1f, 0.75f, 0.1f));
    const float h = 1.0f;
    addQuad(*s, {-h, 0, h}, {h, 0, h}, {h, 0, -h}, {-h, 0, -h}, white);           // floor (+Y)
    addQuad(*s, {-h, 0, -h}, {h, 0, -h}, {h, 2, -h}, {-h, 2, -h}, white);         // back wall (+Z)
    addQuad(*s, {-h, 0, h}, {-h, 0, -h}, {-h, 2, -h}, {-h, 2, h}, red);           // left wall (+X)
    addQuad(*s, {h, 0, -h}, {h, 0, h}, {h, 2, h}, {h, 2, -h}, green);             // right wall (-X)
    addQuad(*s, {-h, 0, h}, {-h, 2, h}, {h, 2, h}, {h, 0, h}, white);             // front wall (-Z), camera inside
    // Ceiling (-Y) with a hole |x|,|z| < 0.3.
    const float a = 0.3f;
    addQuad(*s, {-h, 2, -h}, {h, 2, -h}, {h, 2, -a}, {-h, 2, -a}, white);
    addQuad(*s, {-h, 2, a}, {h, 2, a}, {h, 2, h}, {-h, 2, h}, white);
    addQuad(*s, {-h, 2, -a}, {-a, 2, -a}, {-a, 2, a}, {-h, 2, a}, white);
    addQuad(*s, {a, 2, -a}, {h, 2, -a}, {h, 2, a}, {a, 2, a}, white);
    addBox(*s, {-0.6f, 0.0f, -0.5f}, {-0.1f, 1.2f, 0.0f}, white, false);
    addSun(*s, glm::vec3(-0.8f, -1.0f, -0.15f), 3.5f);
    addCamera(*s, "front", {0.0f, 1.0f, 0.95f}, {0.0f, 0.9f, -1.0f}, 70.0f);
    s->computeBounds();
    return s;
}

}  // namespace deepgi::test
