#include "cli/command.h"

int main(int argc, char** argv)
{
    return groom::cli::run(argc, argv);
}
