#pragma once
//! \file cli.h
//! \brief Command registry of the contour4d tool: each subcommand file adds itself with a
//! `add_*_command` function and returns a closure that runs it.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace c4d::cli {

//! A registered subcommand: the CLI11 node and the action to run when it was chosen.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

void add_phantom_command(CLI::App& root, std::vector<Command>& commands);
void add_evaluate_command(CLI::App& root, std::vector<Command>& commands);
void add_extract_command(CLI::App& root, std::vector<Command>& commands);
void add_reconstruct_command(CLI::App& root, std::vector<Command>& commands);
void add_pack_command(CLI::App& root, std::vector<Command>& commands);
void add_unpack_command(CLI::App& root, std::vector<Command>& commands);
void add_render_command(CLI::App& root, std::vector<Command>& commands);
void add_view_command(CLI::App& root, std::vector<Command>& commands);
void add_export_command(CLI::App& root, std::vector<Command>& commands);

//! Parses argv and runs the chosen subcommand; returns the process exit code. Every
//! c4d::Error becomes its ErrorCode with the message on stderr; nothing else escapes.
int run(int argc, char** argv);

//! True when stdout is a terminal (progress bars and colour only then).
bool stdout_is_terminal();

}  // namespace c4d::cli
