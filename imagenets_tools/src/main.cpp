// `imagenets`: the command line tool (imagenets/tool/command.h).
#include "imagenets/tool/command.h"

int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
