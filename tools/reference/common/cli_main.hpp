// tools/reference/common/cli_main.hpp: the main() of a reference tool with subcommands, so that
// every tool answers the same way: no command -> the usage on stderr, exit 2; --help, -h or
// help -> the usage on stdout, exit 0; a usage_error or std::invalid_argument from the
// command -> "TOOL: message" on stderr, exit 2; any other exception -> exit 1.
#ifndef CLOUDMATH_TOOLS_CLI_MAIN_HPP
#define CLOUDMATH_TOOLS_CLI_MAIN_HPP

#include <algorithm>
#include <functional>
#include <map>
#include <optional>
#include <iostream>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include "strict_number.hpp"

namespace cloudmath::reference {

// The items of a comma-separated list on a command line ("a.csv,b.csv"), empty ones dropped.
inline std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

// A bad command line (the message gets " (see --help)").
struct usage_error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// --flag value pairs after the command; repeatable flags keep every value.
struct flags {
    std::multimap<std::string, std::string> values;
    std::vector<std::string> switches;

    flags(int argc, char** argv, const std::vector<std::string>& known, const std::vector<std::string>& known_switches) {
        for (int i = 2; i < argc; ++i) {
            const std::string f = argv[i];
            if (std::find(known_switches.begin(), known_switches.end(), f) != known_switches.end()) {
                switches.push_back(f);
                continue;
            }
            if (std::find(known.begin(), known.end(), f) == known.end()) throw usage_error("unknown flag '" + f + "'");
            if (i + 1 >= argc) throw usage_error(f + " needs a value");
            values.emplace(f, argv[++i]);
        }
    }
    bool has(const std::string& f) const { return values.count(f) != 0 || std::count(switches.begin(), switches.end(), f) != 0; }
    std::string get(const std::string& f, const std::string& fallback) const {
        const auto it = values.find(f);
        return it == values.end() ? fallback : it->second;
    }
    long long integer(const std::string& f, long long fallback, long long lo, long long hi) const {
        if (!has(f)) return fallback;
        const std::string t = get(f, "");
        const std::optional<long long> parsed = cloudmath::tools::parse_integer<long long>(t);  // strict_number.hpp
        const long long v = parsed.value_or(0);
        if (!parsed || v < lo || v > hi)
            throw usage_error(f + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", not '" +
                              t + "'");
        return v;
    }
};

// run(command) returns the exit status; it throws usage_error for an unknown command.
inline int run_subcommand_tool(const char* tool, const char* usage, int argc, char** argv,
                               const std::function<int(const std::string&)>& run) {
    if (argc < 2) {
        std::cerr << usage;
        return 2;
    }
    const std::string command = argv[1];
    if (command == "--help" || command == "-h" || command == "help") {
        std::cout << usage;
        return 0;
    }
    try {
        return run(command);
    } catch (const usage_error& e) {
        std::cerr << tool << ": " << e.what() << " (see --help)\n";
        return 2;
    } catch (const std::invalid_argument& e) {
        std::cerr << tool << ": " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << tool << ": " << e.what() << '\n';
        return 1;
    }
}

}  // namespace cloudmath::reference

#endif  // CLOUDMATH_TOOLS_CLI_MAIN_HPP
