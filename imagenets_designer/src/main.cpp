// `imagenets-designer`, run as `imagenets designer` (imagenets/tool/command.h).
#include "imagenets/tool/command.h"

int main(int argc, char** argv) { return imagenets::tool::runCommandLine(argc, argv); }
