// SPDX-License-Identifier: MIT
// The `supermodal` command line. Exit status: 0 ok, 2 bad input, 1 internal failure.
#include "cli_app.h"

int main(int argc, char** argv)
{
    return supermodal::cli::run_command_line(argc, argv);
}
