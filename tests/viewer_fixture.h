#pragma once
// The folder of a viewer test run under Xvfb: one per test and process, removed when the test passes and kept (its
// path printed) when it fails, so that the screenshots and the log can be looked at.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace deepgi::test {

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
