#pragma once
// An OpenGL context for off-screen rendering, chosen at run time (--gl, no rebuild):
//   osmesa  Mesa's OSMesa (software, always there on Debian 12; the default);
//   egl     EGL: the device platform (a GPU, or Mesa's software device), else the surfaceless
//           platform; MUJOCO_EGL_DEVICE_ID picks a device by index;
//   auto    egl where it initialises, else osmesa.
// On a CPU, EGL runs Mesa's llvmpipe as OSMesa does, and the images are the same bytes.
// MuJoCo's GL loader looks for EGL in the process before OSMesa, so libEGL is loaded (dlopen)
// only for an EGL context, and one process renders through one API: the first context fixes it.
#include <memory>
#include <optional>
#include <string>

namespace nao::sim {

enum class GlApi { Auto, Egl, OsMesa };

// "auto", "egl", "osmesa"; nullopt for anything else.
std::optional<GlApi> parseGlApi(const std::string& name);
const char* glApiName(GlApi api);

// The API the next context asks for (the command line's --gl; default osmesa). Throws
// nao::Error("--gl", ...) when a context of another API already exists in this process.
void setGlApi(GlApi api);
GlApi glApi();

class GlContext {
 public:
  // Creates a context of glApi() and makes it current. Throws nao::Error("renderer", ...) with
  // what failed (for auto: every try).
  GlContext();
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current; OSMesa's default framebuffer grows to width x height (MuJoCo
  // renders into its own framebuffer object; EGL needs no surface at all).
  void makeCurrent(int width, int height);

  // "osmesa", "egl-device", "egl-surfaceless"; GL_VENDOR, GL_RENDERER.
  const std::string& platform() const;
  const std::string& vendor() const;
  const std::string& renderer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nao::sim
