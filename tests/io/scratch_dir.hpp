// SPDX-License-Identifier: MIT
#pragma once
// A fresh directory per test case, removed afterwards. ctest runs test cases of one executable
// as separate processes, possibly at once, so each gets its own name.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace io_test {

class scratch_dir {
public:
    explicit scratch_dir(const std::string& name) {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() / ("gimlet_io_" + name + "_" + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~scratch_dir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    scratch_dir(const scratch_dir&) = delete;
    scratch_dir& operator=(const scratch_dir&) = delete;
    [[nodiscard]] std::filesystem::path operator/(const std::string& file) const { return path_ / file; }
    [[nodiscard]] const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline std::vector<char> read_bytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void write_bytes(const std::filesystem::path& file, const std::vector<char>& bytes) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace io_test
