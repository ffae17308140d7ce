// cmd_replay.cpp — placeholder until this command family lands (see cli.h).
#include "cli.h"

namespace tandem::cli {

void register_replay_commands(CLI::App&, const GlobalOptions&, std::vector<Command>*) {}

}  // namespace tandem::cli
