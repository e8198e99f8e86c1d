#include "cli/cli_spelling.h"

#include <algorithm>
#include <cstdlib>

namespace softtrace {

std::string nearest_name(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  // Farther than 2 is no suggestion, nor is replacing every letter ("-x" is not "-h").
  const size_t letters = word.size() - std::min(word.find_first_not_of('-'), word.size());
  size_t best_distance = std::min<size_t>(3, letters);
  for (const auto& n : names) {
    const size_t d = edit_distance(word, n);
    if (d < best_distance) {
      best = n;
      best_distance = d;
    }
  }
  return best;
}

namespace {

std::string unknown(const std::string& what, const std::string& word,
                    const std::vector<std::string>& names, const std::string& fallback) {
  const std::string near = nearest_name(word, names);
  return "unknown " + what + " '" + word + "'" +
         (near.empty() ? " (" + fallback + ")" : " (did you mean '" + near + "'?)");
}

bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0';
}

}  // namespace

std::string unknown_word(const CLI::App& app, int argc, const char* const* argv) {
  const CLI::App* current = &app;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;  // everything after is positional
    if (arg.size() > 1 && arg[0] == '-' && !is_number(arg)) {
      // "--name=value"; "-ovalue" and bundled flags "-qv": the first letter names the option.
      const std::string name = arg[1] == '-' ? arg.substr(0, arg.find('=')) : arg.substr(0, 2);
      if (current->get_option_no_throw(name)) continue;
      const std::string word = arg.substr(0, arg.find('='));  // "-width": a long name, one dash
      std::vector<std::string> names;
      for (const CLI::Option* o : current->get_options()) {
        for (const auto& l : o->get_lnames()) names.push_back("--" + l);
        for (const auto& s : o->get_snames()) names.push_back("-" + s);
      }
      const std::string help =
          current == &app ? "softtrace --help" : "softtrace " + current->get_name() + " --help";
      return unknown("option", word, names, "see " + help);
    }
    if (current != &app) continue;  // a value or a positional argument
    const auto subcommands = app.get_subcommands([](const CLI::App*) { return true; });
    const auto found = std::find_if(subcommands.begin(), subcommands.end(),
                                    [&](const CLI::App* s) { return s->get_name() == arg; });
    if (found == subcommands.end()) {
      std::vector<std::string> names;
      for (const CLI::App* s : subcommands) names.push_back(s->get_name());
      return unknown("command", arg, names, "see softtrace --help");
    }
    current = *found;
  }
  return "";
}

}  // namespace softtrace
