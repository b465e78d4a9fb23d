#pragma once
// Included by main.cpp only (the one translation unit that sees CLI11).
//
// A misspelt subcommand or option, refused with the closest name before CLI11 parses: CLI11 2.1
// says only "The following argument was not expected: rnu". An option's number that no double
// holds (1e-400, read as 0) is refused here too, for every option. The command line is walked as
// CLI11 would: a word that names a subcommand of the current command enters it, an option is looked
// up in the current command (and its option groups). Only what is certainly wrong is reported here:
// an unknown option with a close name, and a word where a command without positionals expects
// its subcommand; everything else is left to CLI11.
#include <cctype>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_error.hpp"
#include "rigid/common/did_you_mean.hpp"
#include "rigid/common/number_literal.hpp"

namespace rigid::cli {
namespace detail {

// The command's own options and those of its option groups (unnamed subcommands).
inline std::vector<CLI::Option*> options_of(CLI::App* app) {
  std::vector<CLI::Option*> out = app->get_options();
  for (CLI::App* group : app->get_subcommands([](CLI::App* a) { return a->get_name().empty(); })) {
    const std::vector<CLI::Option*> more = options_of(group);
    out.insert(out.end(), more.begin(), more.end());
  }
  return out;
}

inline std::vector<CLI::App*> named_subcommands(CLI::App* app) {
  return app->get_subcommands([](CLI::App* a) { return !a->get_name().empty(); });
}

// "-1", "-.5", "-1e3": a negative number is a value, not an option (as CLI11 reads it)
inline bool is_number_like(std::string_view a) {
  return a.size() > 1 && a[0] == '-' &&
         (std::isdigit(static_cast<unsigned char>(a[1])) != 0 || a[1] == '.');
}

}  // namespace detail

/// Throws UsageError for a misspelt subcommand (always, with the list and the closest name) or a
/// misspelt option (when a close name exists) in argv; returns otherwise.
inline void refuse_misspelt_names(CLI::App& root, int argc, char** argv) {
  CLI::App* app = &root;
  std::string path = "rigid";
  bool value_next = false;  // the previous word was an option that takes a value
  bool word_seen = false;   // the current command has had a positional word
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--") return;
    if (a.size() > 1 && a[0] == '-' && !detail::is_number_like(a)) {
      if (!a.starts_with("--") &&
          a.size() != 2) {  // -qo: a cluster of short flags, CLI11's to read
        value_next = false;
        continue;
      }
      const std::string name(a.substr(0, a.find('=')));
      const std::vector<CLI::Option*> options = detail::options_of(app);
      const CLI::Option* known = nullptr;
      for (const CLI::Option* o : options) {
        if (o->check_name(name)) known = o;
      }
      if (known != nullptr) {
        value_next = a.find('=') == std::string_view::npos && known->get_items_expected_max() > 0;
        // a number that no double holds (1e-400 would be read as 0, 1e-310 as a subnormal)
        const std::string_view value = value_next && i + 1 < argc ? std::string_view(argv[i + 1])
                                       : a.find('=') != std::string_view::npos
                                           ? a.substr(a.find('=') + 1)
                                           : std::string_view{};
        if (auto problem = literal_range_problem(value)) {
          throw UsageError(fmt::format("{} {}: {}", name, value, *problem));
        }
        continue;
      }
      std::vector<std::string> names;
      for (const CLI::Option* o : options) {
        for (const std::string& l : o->get_lnames()) names.push_back("--" + l);
        for (const std::string& s : o->get_snames()) names.push_back("-" + s);
      }
      if (auto guess = did_you_mean(name, names)) {
        throw UsageError(
            fmt::format("unknown option '{}' for `{}`; did you mean '{}'?", name, path, *guess));
      }
      value_next = false;
      continue;
    }
    if (value_next) {  // the value of the option before
      value_next = false;
      continue;
    }
    const std::string word(a);
    CLI::App* sub = nullptr;
    for (CLI::App* s : detail::named_subcommands(app)) {
      if (s->check_name(word)) sub = s;
    }
    if (sub != nullptr) {
      app = sub;
      path += " " + word;  // as typed (an alias: `rigid inertia cone`)
      word_seen = false;
      continue;
    }
    const bool takes_positionals =
        !app->get_options([](const CLI::Option* o) { return o->get_positional(); }).empty() ||
        app->get_allow_extras();
    if (!word_seen && !takes_positionals && !detail::named_subcommands(app).empty()) {
      std::vector<std::string> names;
      for (CLI::App* s : detail::named_subcommands(app)) names.push_back(s->get_name());
      throw UsageError(fmt::format("unknown subcommand '{}' of `{}`{}; expected one of {}", word,
                                   path, did_you_mean_hint(word, names), fmt::join(names, ", ")));
    }
    word_seen = true;
  }
}

}  // namespace rigid::cli
