// Tests of tools/common: atomic_file.hpp (a failed write leaves the old file and no
// temporary; the failures are produced with RLIMIT_FSIZE, which stops writes to regular
// files even for root, /dev/full and a directory in the way), strict_number.hpp and
// gzip_text.hpp (checked against the system's gzip where one is installed).
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include "atomic_file.hpp"
#include "gzip_text.hpp"
#include "strict_number.hpp"

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/stat.h>

namespace fs = std::filesystem;
using cloudmath::tools::check_output_path;
using cloudmath::tools::parse_count;
using cloudmath::tools::parse_finite;
using cloudmath::tools::parse_integer;
using cloudmath::tools::write_file_atomically;

namespace {

// A fresh, empty scratch directory per test case.
fs::path scratch(const std::string& name) {
    const fs::path dir = fs::current_path() / ("tools_common_scratch_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// The names in dir, sorted.
std::vector<std::string> listing(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

// Lowers the file-size limit to `bytes` for its lifetime (SIGXFSZ ignored, so write()
// fails with EFBIG instead of killing the process), then restores it.
class file_size_limit {
public:
    explicit file_size_limit(rlim_t bytes) {
        ::getrlimit(RLIMIT_FSIZE, &old_);
        old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
        rlimit lowered = old_;
        lowered.rlim_cur = bytes;
        ::setrlimit(RLIMIT_FSIZE, &lowered);
    }
    ~file_size_limit() {
        ::setrlimit(RLIMIT_FSIZE, &old_);
        std::signal(SIGXFSZ, old_handler_);
    }
    file_size_limit(const file_size_limit&) = delete;
    file_size_limit& operator=(const file_size_limit&) = delete;

private:
    rlimit old_{};
    void (*old_handler_)(int) = SIG_DFL;
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a new file: written whole, no temporary left, the umask's permissions") {
    const fs::path dir = scratch("new");
    const std::string path = (dir / "out.csv").string();
    std::string big(3 * 1024 * 1024 + 17, 'x');  // several write() calls' worth
    big[12345] = '\0';
    CHECK(write_file_atomically(path, big).empty());
    CHECK(read(path) == big);
    CHECK(listing(dir) == std::vector<std::string>{"out.csv"});
    const mode_t mask = ::umask(0);
    ::umask(mask);
    struct stat st {};
    REQUIRE(::stat(path.c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == (0666 & ~mask));
    CHECK(write_file_atomically(path, "", true).empty());  // empty content, with fsync
    CHECK(read(path).empty());
}

TEST_CASE("replacing a file keeps its permissions; a link keeps pointing at it") {
    const fs::path dir = scratch("replace");
    const fs::path file = dir / "data.txt";
    put(file, "old contents");
    ::chmod(file.c_str(), 0640);
    fs::create_symlink("data.txt", dir / "link.txt");
    CHECK(write_file_atomically((dir / "link.txt").string(), "new").empty());
    CHECK(fs::is_symlink(dir / "link.txt"));
    CHECK(read(file) == "new");
    struct stat st {};
    REQUIRE(::stat(file.c_str(), &st) == 0);
    CHECK((st.st_mode & 0777) == 0640);
    CHECK(listing(dir) == std::vector<std::string>{"data.txt", "link.txt"});
}

TEST_CASE("a failed write (file size limit) leaves the old file and no temporary") {
    const fs::path dir = scratch("limit");
    const fs::path file = dir / "image.png";
    put(file, "the old image");
    std::string error;
    {
        const file_size_limit limit(4);
        error = write_file_atomically(file.string(), "a longer new image");
    }
    CHECK(contains(error, "cannot write '" + file.string() + "'"));
    CHECK(contains(error, std::strerror(EFBIG)));
    CHECK(read(file) == "the old image");
    CHECK(listing(dir) == std::vector<std::string>{"image.png"});
    // The same limit and no old file: nothing at all is left.
    fs::remove(file);
    {
        const file_size_limit limit(0);
        error = write_file_atomically(file.string(), "bytes");
    }
    CHECK(!error.empty());
    CHECK(listing(dir).empty());
}

TEST_CASE("devices are written in place: /dev/full fails, /dev/null works, both stay devices") {
    if (!fs::exists("/dev/full") || !fs::exists("/dev/null")) return;
    const std::string error = write_file_atomically("/dev/full", "bytes");
    CHECK(contains(error, "cannot write '/dev/full'"));
    CHECK(contains(error, std::strerror(ENOSPC)));
    CHECK(write_file_atomically("/dev/null", "bytes").empty());
    CHECK(fs::is_character_file("/dev/full"));
    CHECK(fs::is_character_file("/dev/null"));
    CHECK(check_output_path("/dev/null").empty());
}

TEST_CASE("a missing directory, a directory in the way, an empty path: errors naming the path") {
    const fs::path dir = scratch("errors");
    const std::string missing = (dir / "no_such_dir" / "out.csv").string();
    CHECK(contains(write_file_atomically(missing, "x"), missing));
    CHECK(contains(check_output_path(missing), missing));
    fs::create_directory(dir / "sub");
    const std::string sub = (dir / "sub").string();
    CHECK(contains(write_file_atomically(sub, "x"), std::strerror(EISDIR)));
    CHECK(contains(check_output_path(sub), std::strerror(EISDIR)));
    CHECK(fs::is_directory(sub));
    CHECK(!write_file_atomically("", "x").empty());
    CHECK(listing(dir) == std::vector<std::string>{"sub"});
}

TEST_CASE("check_output_path creates nothing and leaves an existing file alone") {
    const fs::path dir = scratch("check");
    CHECK(check_output_path((dir / "new.csv").string()).empty());
    CHECK(listing(dir).empty());
    put(dir / "old.csv", "kept");
    CHECK(check_output_path((dir / "old.csv").string()).empty());
    CHECK(read(dir / "old.csv") == "kept");
    CHECK(listing(dir) == std::vector<std::string>{"old.csv"});
}

TEST_CASE("parse_finite: the whole text, finite, decimal") {
    CHECK(parse_finite("0.067") == 0.067);
    CHECK(parse_finite("-2.5e-3") == -2.5e-3);
    CHECK(parse_finite("+1") == 1.0);
    CHECK(parse_finite(".5") == 0.5);
    CHECK(parse_finite("1e300") == 1e300);
    for (const char* bad : {"", " ", "0.067xyz", "1 ", " 1", "nan", "NaN", "-nan", "inf", "-inf", "infinity",
                            "1e999", "0x10", "1,5", "+", "-", "++1", "+-1", "e5", "1e"}) {
        CAPTURE(bad);
        CHECK(!parse_finite(bad));
    }
}

TEST_CASE("parse_integer: decimal digits in the type's range") {
    CHECK(parse_integer<int>("-12") == -12);
    CHECK(parse_integer<int>("+7") == 7);
    CHECK(parse_integer<unsigned>("4294967295") == 4294967295u);
    CHECK(parse_integer<std::uint64_t>("18446744073709551615") == 18446744073709551615ull);
    for (const char* bad : {"", "-1", "1.5", "1e3", " 1", "1 ", "0x1", "4294967296", "abc", "-"}) {
        CAPTURE(bad);
        CHECK(!parse_integer<unsigned>(bad));
    }
    CHECK(!parse_integer<int>("2147483648"));
    CHECK(!parse_integer<int>("--1"));
}

TEST_CASE("parse_count: non-negative whole numbers, digits or exponent forms") {
    CHECK(parse_count("0") == 0u);
    CHECK(parse_count("2000000") == 2000000u);
    CHECK(parse_count("1e6") == 1000000u);
    CHECK(parse_count("1.5e3") == 1500u);
    CHECK(parse_count("18446744073709551615") == 18446744073709551615ull);
    CHECK(parse_count("9007199254740992") == 9007199254740992ull);
    for (const char* bad : {"", "-5", "-0", "2.5", "1e300", "nan", "inf", "1e6x", " 5", "5 ", "0x10", "-1e6"}) {
        CAPTURE(bad);
        CHECK(!parse_count(bad));
    }
}

// A text like the stored truths: metadata, a header, rows of numbers.
std::string truth_like_text(int rows) {
    std::string text = "# preset: ground\nx,y,r,g,b\n";
    for (int i = 0; i < rows; ++i)
        text += std::to_string(i % 160) + "," + std::to_string(i / 160) + "," + std::to_string(0.001 * (i % 997)) + ",0.5," +
                std::to_string(i) + "\n";
    return text;
}

TEST_CASE("gzip_text: a round trip keeps every byte, and the same text gives the same bytes") {
    for (const std::string& text : {std::string(), std::string("x"), truth_like_text(14400), std::string(3u << 20, 'a')}) {
        CAPTURE(text.size());
        const std::string z = cloudmath::tools::gzip_compress(text);
        CHECK(cloudmath::tools::is_gzip(z));
        CHECK(cloudmath::tools::gunzip(z, "t") == text);
        CHECK(cloudmath::tools::gzip_compress(text) == z);  // deterministic: no name, mtime 0
    }
    const std::string text = truth_like_text(14400);
    CHECK(cloudmath::tools::gzip_compress(text).size() * 3 < text.size());  // worth storing
}

TEST_CASE("gzip_text: read_data_file reads plain and gzip files alike; the system's gzip agrees") {
    const fs::path dir = scratch("gzip_read");
    const std::string text = truth_like_text(2000);
    put(dir / "plain.csv", text);
    put(dir / "packed.csv.gz", cloudmath::tools::gzip_compress(text));
    CHECK(cloudmath::tools::read_data_file((dir / "plain.csv").string()) == text);
    CHECK(cloudmath::tools::read_data_file((dir / "packed.csv.gz").string()) == text);
    if (std::system("command -v gzip >/dev/null 2>&1") == 0) {
        // Ours read by gzip, and gzip's read by ours.
        REQUIRE(std::system(("gzip -dc '" + (dir / "packed.csv.gz").string() + "' > '" + (dir / "by_gzip.csv").string() + "'").c_str()) == 0);
        CHECK(read(dir / "by_gzip.csv") == text);
        REQUIRE(std::system(("gzip -9nc '" + (dir / "plain.csv").string() + "' > '" + (dir / "theirs.gz").string() + "'").c_str()) == 0);
        CHECK(cloudmath::tools::read_data_file((dir / "theirs.gz").string()) == text);
    }
    try {
        (void)cloudmath::tools::read_data_file((dir / "missing.csv.gz").string());
        FAIL("a missing file was read");
    } catch (const std::runtime_error& e) {
        CHECK(contains(e.what(), "missing.csv.gz"));
    }
}

TEST_CASE("gzip_text: damaged, truncated, padded and oversized streams are errors naming the file") {
    const std::string text = truth_like_text(2000);
    const std::string z = cloudmath::tools::gzip_compress(text);
    std::string damaged = z;
    damaged[z.size() / 2] = static_cast<char>(damaged[z.size() / 2] ^ 0x55);
    std::string bad_crc = z;
    bad_crc[z.size() - 6] = static_cast<char>(bad_crc[z.size() - 6] ^ 0x01);  // the CRC-32 in the trailer
    const std::string cases[][2] = {{damaged, "damaged"},
                                    {bad_crc, "damaged"},
                                    {z.substr(0, z.size() / 2), "truncated"},
                                    {z.substr(0, z.size() - 1), "truncated"},
                                    {z + "junk", "after the end"}};
    for (const auto& c : cases) {
        CAPTURE(c[1]);
        try {
            (void)cloudmath::tools::gunzip(c[0], "truth_x.csv.gz");
            FAIL("a bad stream was read");
        } catch (const std::runtime_error& e) {
            CHECK(contains(e.what(), "truth_x.csv.gz"));
            CHECK(contains(e.what(), c[1]));
        }
    }
    CHECK_THROWS_WITH_AS((void)cloudmath::tools::gunzip(z, "big.gz", 1000), doctest::Contains("more than 1000 bytes"),
                         std::runtime_error);
}
