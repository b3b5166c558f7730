// A small command-line parser shared by the subcommands: --name value, --name=value, flags, repeated
// options; unknown options and missing values throw UsageError with the command's usage text.
#pragma once

#include <string>
#include <vector>

#include "app/commands.h"

namespace bounce::app {

struct OptionSpec {
    std::string name; // without the dashes
    bool takesValue = true;
    bool repeatable = false;
};

class Options {
public:
    // Throws UsageError (with `usage` appended) for unknown options or missing values. `positional`
    // collects the arguments that are not options.
    Options(const Args& args, const std::vector<OptionSpec>& specs, const std::string& usage);

    bool helpRequested() const { return help_; }
    bool has(const std::string& name) const;
    std::string get(const std::string& name, const std::string& fallback = {}) const;
    std::vector<std::string> all(const std::string& name) const;
    const std::vector<std::string>& positional() const { return positional_; }

    int getInt(const std::string& name, int fallback, int min, int max) const;
    double getDouble(const std::string& name, double fallback, double min, double max) const;
    const std::string& usage() const { return usage_; }

private:
    std::vector<std::pair<std::string, std::string>> values_;
    std::vector<std::string> positional_;
    std::string usage_;
    bool help_ = false;
};

// "512x512" -> {512, 512}; throws UsageError for anything else or sizes outside 1..16384.
void parseSize(const std::string& text, int& width, int& height);

} // namespace bounce::app
