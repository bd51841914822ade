#include "sim/GlContext.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "robot/Error.h"

namespace nao::sim {

namespace {

const char* const kWhere = "renderer";

std::mutex gMutex;
GlApi gRequested = GlApi::OsMesa;
std::optional<GlApi> gInUse;  // the API of the first context made in this process

using GetString = const unsigned char* (*)(unsigned int);

std::string glString(GetString get, unsigned int name) {
  const unsigned char* s = get ? get(name) : nullptr;
  return s ? reinterpret_cast<const char*>(s) : "";
}

// libEGL's entry points, resolved by hand: linking libEGL would put eglGetProcAddress into
// every process, where MuJoCo's loader would take it even for an OSMesa context.
struct Egl {
  void* lib = nullptr;
  PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
  PFNEGLGETERRORPROC getError = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLTERMINATEPROC terminate = nullptr;
  PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
  PFNEGLBINDAPIPROC bindApi = nullptr;
  PFNEGLCREATECONTEXTPROC createContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
  PFNEGLQUERYSTRINGPROC queryString = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;

  template <class F>
  void resolve(F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(lib, name));
    if (!f && getProcAddress) f = reinterpret_cast<F>(getProcAddress(name));
  }

  // Empty, or why libEGL cannot be used.
  std::string load() {
    // Local first: until a context works, nothing of EGL is visible to MuJoCo's loader.
    lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) return "libEGL.so.1 not found (Debian: libegl1, libegl-mesa0)";
    resolve(getProcAddress, "eglGetProcAddress");
    resolve(getError, "eglGetError");
    resolve(initialize, "eglInitialize");
    resolve(terminate, "eglTerminate");
    resolve(chooseConfig, "eglChooseConfig");
    resolve(bindApi, "eglBindAPI");
    resolve(createContext, "eglCreateContext");
    resolve(destroyContext, "eglDestroyContext");
    resolve(makeCurrent, "eglMakeCurrent");
    resolve(queryString, "eglQueryString");
    resolve(getPlatformDisplay, "eglGetPlatformDisplayEXT");
    resolve(queryDevices, "eglQueryDevicesEXT");
    resolve(queryDeviceString, "eglQueryDeviceStringEXT");
    if (!getProcAddress || !getError || !initialize || !terminate || !chooseConfig || !bindApi || !createContext ||
        !destroyContext || !makeCurrent || !getPlatformDisplay)
      return "libEGL.so.1 lacks eglGetPlatformDisplayEXT or a core function";
    return "";
  }

  std::string error(const char* what) const {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(getError()));
    return std::string(what) + " failed (EGL error " + code + ")";
  }
};

// libOSMesa's entry points, resolved by hand like EGL's: linked, it would load LLVM into every
// process, rendering or not (90 ms at each start).
struct OsMesa {
  void* lib = nullptr;
  decltype(&OSMesaCreateContextExt) createContextExt = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;

  // Empty, or why libOSMesa cannot be used.
  std::string load() {
    for (const char* name : {"libOSMesa.so.8", "libOSMesa.so"})
      if ((lib = dlopen(name, RTLD_NOW | RTLD_LOCAL))) break;
    if (!lib) return "libOSMesa.so.8 not found (Debian: libosmesa6)";
    createContextExt = reinterpret_cast<decltype(createContextExt)>(dlsym(lib, "OSMesaCreateContextExt"));
    destroyContext = reinterpret_cast<decltype(destroyContext)>(dlsym(lib, "OSMesaDestroyContext"));
    makeCurrent = reinterpret_cast<decltype(makeCurrent)>(dlsym(lib, "OSMesaMakeCurrent"));
    getProcAddress = reinterpret_cast<decltype(getProcAddress)>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!createContextExt || !destroyContext || !makeCurrent || !getProcAddress) return "libOSMesa lacks a core function";
    return "";
  }
};

// The EGL device to open: MUJOCO_EGL_DEVICE_ID's, else the first that is not Mesa's software
// device (a GPU), else the first. Empty with why when there is none.
std::string chooseDevice(Egl& egl, EGLDeviceEXT& device, bool& software) {
  if (!egl.queryDevices) return "no EGL_EXT_device_enumeration";
  EGLint n = 0;
  if (!egl.queryDevices(0, nullptr, &n) || n <= 0) return "no EGL device";
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(n));
  if (!egl.queryDevices(n, devices.data(), &n)) return egl.error("eglQueryDevicesEXT");
  auto isSoftware = [&](EGLDeviceEXT d) {
    const char* ext = egl.queryDeviceString ? egl.queryDeviceString(d, EGL_EXTENSIONS) : nullptr;
    return ext && std::string(ext).find("EGL_MESA_device_software") != std::string::npos;
  };
  if (const char* id = std::getenv("MUJOCO_EGL_DEVICE_ID"); id && *id) {
    char* end = nullptr;
    const long k = std::strtol(id, &end, 10);
    if (*end != '\0' || k < 0 || k >= n)
      throw Error("MUJOCO_EGL_DEVICE_ID", "'" + std::string(id) + "' is not a device index 0.." + std::to_string(n - 1));
    device = devices[static_cast<std::size_t>(k)];
    software = isSoftware(device);
    return "";
  }
  device = devices[0];
  for (EGLDeviceEXT d : devices)
    if (!isSoftware(d)) {
      device = d;
      break;
    }
  software = isSoftware(device);
  return "";
}

}  // namespace

std::optional<GlApi> parseGlApi(const std::string& name) {
  if (name == "auto") return GlApi::Auto;
  if (name == "egl") return GlApi::Egl;
  if (name == "osmesa") return GlApi::OsMesa;
  return std::nullopt;
}

const char* glApiName(GlApi api) {
  switch (api) {
    case GlApi::Egl: return "egl";
    case GlApi::OsMesa: return "osmesa";
    case GlApi::Auto: break;
  }
  return "auto";
}

void setGlApi(GlApi api) {
  std::lock_guard<std::mutex> lock(gMutex);
  if (gInUse && api != GlApi::Auto && api != *gInUse)
    throw Error("--gl", std::string("this process already renders through ") + glApiName(*gInUse));
  gRequested = api;
}

GlApi glApi() {
  std::lock_guard<std::mutex> lock(gMutex);
  return gRequested;
}

struct GlContext::Impl {
  std::string platform, vendor, renderer;
  // OSMesa
  OsMesa mesa;
  OSMesaContext osmesa = nullptr;
  std::vector<unsigned char> buffer;  // its default framebuffer
  int bufferWidth = 0, bufferHeight = 0;
  // EGL
  Egl egl;
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;

  // Empty, or why not.
  std::string tryEgl(bool device) {
    if (!egl.lib) {
      if (std::string why = egl.load(); !why.empty()) return why;
    }
    bool software = false;
    if (device) {
      EGLDeviceEXT d = nullptr;
      if (std::string why = chooseDevice(egl, d, software); !why.empty()) return why;
      display = egl.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, d, nullptr);
    } else {
      display = egl.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    }
    if (display == EGL_NO_DISPLAY) return egl.error("eglGetPlatformDisplayEXT");
    EGLint major = 0, minor = 0;
    if (!egl.initialize(display, &major, &minor)) {
      const std::string why = egl.error("eglInitialize");
      display = EGL_NO_DISPLAY;
      return why;
    }
    const EGLint attributes[] = {EGL_RED_SIZE,          8,
                                 EGL_GREEN_SIZE,        8,
                                 EGL_BLUE_SIZE,         8,
                                 EGL_ALPHA_SIZE,        8,
                                 EGL_DEPTH_SIZE,        24,
                                 EGL_STENCIL_SIZE,      8,
                                 EGL_COLOR_BUFFER_TYPE, EGL_RGB_BUFFER,
                                 EGL_SURFACE_TYPE,      EGL_PBUFFER_BIT,
                                 EGL_RENDERABLE_TYPE,   EGL_OPENGL_BIT,
                                 EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    std::string why;
    if (!egl.chooseConfig(display, attributes, &config, 1, &configs) || configs < 1)
      why = "no EGL config with RGBA8, depth 24, stencil 8 for desktop OpenGL";
    else if (!egl.bindApi(EGL_OPENGL_API))
      why = egl.error("eglBindAPI(EGL_OPENGL_API)");
    else if ((context = egl.createContext(display, config, EGL_NO_CONTEXT, nullptr)) == EGL_NO_CONTEXT)
      why = egl.error("eglCreateContext");
    else if (!egl.makeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
      why = egl.error("eglMakeCurrent");
    if (!why.empty()) {
      if (context != EGL_NO_CONTEXT) egl.destroyContext(display, context);
      context = EGL_NO_CONTEXT;
      egl.terminate(display);
      display = EGL_NO_DISPLAY;
      return why;
    }
    // From now on MuJoCo's loader must find EGL: make its symbols global.
    dlopen("libEGL.so.1", RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD);
    platform = device ? "egl-device" : "egl-surfaceless";
    const auto get = reinterpret_cast<GetString>(egl.getProcAddress("glGetString"));
    vendor = glString(get, GL_VENDOR);
    renderer = glString(get, GL_RENDERER);
    if (device && std::getenv("MUJOCO_EGL_DEVICE_ID") && software)
      std::fprintf(stderr, "renderer: MUJOCO_EGL_DEVICE_ID chose Mesa's software device (%s), not a GPU\n",
                   renderer.c_str());
    return "";
  }

  std::string tryOsMesa() {
    if (!mesa.lib) {
      if (std::string why = mesa.load(); !why.empty()) return why;
    }
    osmesa = mesa.createContextExt(OSMESA_RGBA, 24, 8, 8, nullptr);
    if (!osmesa) return "OSMesaCreateContextExt failed";
    resize(1, 1);
    // From now on MuJoCo's loader must find OSMesaGetProcAddress: make the library's symbols global.
    if (!dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD)) dlopen("libOSMesa.so", RTLD_NOW | RTLD_GLOBAL | RTLD_NOLOAD);
    platform = "osmesa";
    const auto get = reinterpret_cast<GetString>(mesa.getProcAddress("glGetString"));
    vendor = glString(get, GL_VENDOR);
    renderer = glString(get, GL_RENDERER);
    return "";
  }

  void resize(int width, int height) {
    if (width > bufferWidth || height > bufferHeight) {
      bufferWidth = std::max(width, bufferWidth);
      bufferHeight = std::max(height, bufferHeight);
      buffer.assign(static_cast<std::size_t>(bufferWidth) * bufferHeight * 4, 0);
    }
    if (!mesa.makeCurrent(osmesa, buffer.data(), GL_UNSIGNED_BYTE, bufferWidth, bufferHeight))
      throw Error(kWhere, "OSMesaMakeCurrent failed");
  }
};

GlContext::GlContext() : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  std::lock_guard<std::mutex> lock(gMutex);
  // auto keeps to the API this process already renders through.
  const GlApi api = gRequested == GlApi::Auto && gInUse ? *gInUse : gRequested;
  std::string tried;
  auto attempt = [&](const char* name, const std::string& why) {
    if (why.empty()) return true;
    tried += (tried.empty() ? "" : "; ") + std::string(name) + ": " + why;
    return false;
  };
  bool made = false;
  if (api != GlApi::OsMesa) made = attempt("EGL device", I.tryEgl(true)) || attempt("EGL surfaceless", I.tryEgl(false));
  if (!made && api != GlApi::Egl) made = attempt("OSMesa", I.tryOsMesa());
  if (!made) throw Error(kWhere, std::string("no OpenGL context (--gl ") + glApiName(api) + "): " + tried);
  gInUse = I.platform == "osmesa" ? GlApi::OsMesa : GlApi::Egl;
}

GlContext::~GlContext() {
  Impl& I = *impl_;
  if (I.osmesa) I.mesa.destroyContext(I.osmesa);
  if (I.context != EGL_NO_CONTEXT) {
    I.egl.makeCurrent(I.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    I.egl.destroyContext(I.display, I.context);
  }
  // The display stays initialised: other contexts of this process may share it (eglTerminate
  // would end them too), and the library stays loaded for MuJoCo's loader.
}

void GlContext::makeCurrent(int width, int height) {
  Impl& I = *impl_;
  if (I.osmesa) {
    I.resize(width, height);
  } else if (!I.egl.makeCurrent(I.display, EGL_NO_SURFACE, EGL_NO_SURFACE, I.context)) {
    throw Error(kWhere, I.egl.error("eglMakeCurrent"));
  }
}

const std::string& GlContext::platform() const { return impl_->platform; }
const std::string& GlContext::vendor() const { return impl_->vendor; }
const std::string& GlContext::renderer() const { return impl_->renderer; }

}  // namespace nao::sim
