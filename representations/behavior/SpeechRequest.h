#pragma once
// What the robot says: a new id is a new utterance, said once (the backend's speech output:
// the event log in the simulator, the text-to-speech command on a NAO).
#include <string>

namespace nao {

struct SpeechRequest {
  std::string text;
  int id = 0;  // 0: nothing said yet
};

}  // namespace nao
