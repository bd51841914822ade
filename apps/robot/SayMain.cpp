// nao-soccer-say: the robot's voice in the bundle (nao-soccer-robot's --speech-command on a NAO,
// robot/deploy/nao-soccer-start). Flite with its kal voice, linked from Debian's static archives,
// so that the bundle carries one small program and ALSA's library instead of flite's 30 MB of
// voices. NAOqi's own text-to-speech starts minutes after boot and is not used.
// usage: nao-soccer-say TEXT [WAV]   (WAV: write the speech to this file instead of playing it)
// Exit 0 spoken, 1 nothing could be played or written, 2 bad usage.
#include <cstdio>
#include <cstring>

extern "C" {
#include <flite/flite.h>
cst_voice* register_cmu_us_kal(const char* voxdir);
}

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3 || std::strlen(argv[1]) == 0) {
    std::fprintf(stderr, "usage: nao-soccer-say TEXT [WAV]\n");
    return 2;
  }
  flite_init();
  cst_voice* voice = register_cmu_us_kal(nullptr);
  if (!voice) {
    std::fprintf(stderr, "nao-soccer-say: the kal voice did not load\n");
    return 1;
  }
  const char* out = argc == 3 ? argv[2] : "play";
  const float seconds = flite_text_to_speech(argv[1], voice, out);
  if (!(seconds > 0)) {
    if (argc == 3) std::fprintf(stderr, "nao-soccer-say: nothing written to %s\n", out);
    else std::fprintf(stderr, "nao-soccer-say: nothing played (no audio device?)\n");
    return 1;
  }
  return 0;
}
