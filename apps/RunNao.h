#pragma once
// `nao-soccer run --backend nao`: the robot program on a real NAO V6 (LoLA + V4L2), with the
// GameController and the buttons. Options beyond the common ones are listed here.
#include <vector>

#include "apps/Cli.h"

namespace nao::cli {

std::vector<Option> naoRunOptions();
int runNao(const Args& args);

}  // namespace nao::cli
