// tools/reference/cli_main.hpp: the main() of a reference tool with subcommands, so that
// every tool answers the same way: no command -> the usage on stderr, exit 2; --help, -h or
// help -> the usage on stdout, exit 0; a usage_error or std::invalid_argument from the
// command -> "TOOL: message" on stderr, exit 2; any other exception -> exit 1.
#ifndef CLOUDMATH_TOOLS_CLI_MAIN_HPP
#define CLOUDMATH_TOOLS_CLI_MAIN_HPP

#include <functional>
#include <iostream>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

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
