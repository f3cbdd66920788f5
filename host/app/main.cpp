#include "app/commands.h"

int main(int argc, char** argv) { return vkray::vkrayMain(argc, argv); }
