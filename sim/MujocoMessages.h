#pragma once
// MuJoCo's warnings and errors as the project's one-line messages: a warning goes to stderr as
// one line (never to stdout, where it would break `--json -`), an error becomes an exception
// (nao::RunFailure("MuJoCo", ...)); MuJoCo then never writes MUJOCO_LOG.TXT. Idempotent.
namespace nao::sim {

void routeMujocoMessages();

}  // namespace nao::sim
