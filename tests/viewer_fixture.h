#pragma once
// The folder of a viewer test run under Xvfb: one per test and process, removed when the test passes and kept (its
// path printed) when it fails, so that the screenshots and the log can be looked at.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

namespace deepgi::test {

struct XvfbRun {
    int rc = -1;      // the viewer's exit status
    std::string log;  // what the command wrote to its log file
};

// Runs a shell command that starts the viewer under xvfb-run and writes its output to `log`. xvfb-run exits 5 when it
// cannot remove its own temporary folder, whatever the viewer did (seen with several xvfb-run -a at once; once twice
// in a row, and once without its message in the log): that run's status is lost, so it runs again. deepgi never
// exits 5 (it exits 0, 1, or CLI11's codes of 100 and above).
inline XvfbRun runUnderXvfb(const std::string& cmd, const std::string& log) {
    XvfbRun r;
    for (int attempt = 0; attempt < 4; ++attempt) {
        if (attempt > 0) std::this_thread::sleep_for(std::chrono::seconds(1));
        const int status = std::system(cmd.c_str());
        r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        std::ifstream in(log);
        r.log.assign(std::istreambuf_iterator<char>(in), {});
        if (r.rc != 5) break;
    }
    return r;
}

class ViewerTestFolder : public ::testing::Test {
protected:
    explicit ViewerTestFolder(std::string prefix) : prefix_(std::move(prefix)) {}
    void SetUp() override {
        ASSERT_EQ(std::system("command -v xvfb-run > /dev/null 2>&1"), 0)
            << "xvfb-run is missing: install xvfb and xauth (tools/install-deps.sh)";
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = std::filesystem::temp_directory_path() / (prefix_ + std::string(info->name()) + "_" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_);
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override {
        if (!HasFailure()) std::filesystem::remove_all(dir_);
        else std::fprintf(stderr, "viewer test files kept in %s\n", dir_.c_str());
    }
    std::string path(const std::string& name) const { return (dir_ / name).string(); }
    std::filesystem::path dir_;

private:
    std::string prefix_;
};

}  // namespace deepgi::test
