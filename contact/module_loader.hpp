#pragma once
// grains's optional modules: shared libraries built beside the program and
// loaded (dlopen) the first time a feature needs them, so that a run which
// does not use the feature never maps the large libraries behind it (OpenVDB
// for the sphere decomposition of meshes, contact/clump/vdb; VTK's rendering
// and OpenGL for `grains render`, postprocess/render). Here, in the lowest
// layer, so that every layer's modules share one loader.
#include <string>

namespace grains {

struct ModuleSpec {
  const char* env_var;       // a path the user gives; if set, the only place looked at
  const char* build_path;    // where the build put the module (may be null)
  const char* file_name;     // its file name, looked for beside the program and by the loader's search path
  const char* symbol;        // the entry point
  const char* needed_for;    // what needs it, for the error ("the sphere decomposition of a mesh")
  const char* what;          // what the module holds ("OpenVDB")
};

/// The entry point of a module, loaded from $env_var if set (and only
/// there), else from build_path, else beside the running program, else by
/// the loader's search path; the module stays loaded to the end of the
/// process. Looked up once per process and entry point (thread-safe): the
/// pointer, or the failure, is kept. Throws std::runtime_error saying what
/// is missing, how to point at it and every path tried with the loader's
/// reason.
void* module_symbol(const ModuleSpec& spec);

}  // namespace grains
