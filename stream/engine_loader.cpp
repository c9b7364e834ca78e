// SPDX-License-Identifier: Apache-2.0
// loadStreamEngine: dlopen() of the module, looked up where the build tree and the install put it.
#include "stream/engine_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <unistd.h>

#include <atomic>
#include <mutex>
#include <vector>

namespace overlayd {
namespace {

// The running binary's folder: the build tree puts the module there, beside build/daemon/overlayd.
std::string executableFolder()
{
    std::string path(4096, '\0');
    const ssize_t length = readlink("/proc/self/exe", path.data(), path.size());
    if (length <= 0 || size_t(length) >= path.size())
        return {};
    path.resize(size_t(length));
    return path.substr(0, path.rfind('/'));
}

struct Module {
    void *handle = nullptr;
    CreateEngineFunction create = nullptr;
    CheckEncoderFunction check = nullptr;
    CheckTlsFunction checkTls = nullptr;
    std::string error;
};

Module openModule()
{
    Module module;
    std::vector<std::string> places;
    // The environment first: a module built or installed elsewhere.
    if (const char *folder = std::getenv("OVERLAYD_STREAM_MODULE_DIR"); folder && *folder)
        places.push_back(std::string(folder) + "/" + kModuleFileName);
    if (const std::string folder = executableFolder(); !folder.empty()) {
        places.push_back(folder + "/" + kModuleFileName);
        places.push_back(folder + "/" + kPackagedModuleDir + "/" + kModuleFileName);
    }
    places.push_back(std::string(OVERLAYD_STREAM_MODULE_DIR) + "/" + kModuleFileName);
    std::string tried;
    for (const std::string &place : places) {
        if (access(place.c_str(), F_OK) != 0) {
            tried += (tried.empty() ? "" : ", ") + place;
            continue;
        }
        module.handle = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (module.handle == nullptr) {
            const char *why = dlerror();
            module.error = "cannot load " + place + ": " + (why ? why : "?");
            return module;
        }
        module.create = reinterpret_cast<CreateEngineFunction>(dlsym(module.handle, kCreateEngineSymbol));
        module.check = reinterpret_cast<CheckEncoderFunction>(dlsym(module.handle, kCheckEncoderSymbol));
        module.checkTls = reinterpret_cast<CheckTlsFunction>(dlsym(module.handle, kCheckTlsSymbol));
        if (module.create == nullptr || module.check == nullptr || module.checkTls == nullptr)
            module.error = place + " has no " + kCreateEngineSymbol + ": not an overlayd stream module";
        return module;
    }
    module.error =
        std::string("the encoded outputs' module ") + kModuleFileName + " is not installed (looked in " + tried + ")";
    return module;
}

std::atomic<bool> moduleRequired{false};

const Module &theModule()
{
    static std::once_flag once;
    static Module module;
    std::call_once(once, [] { module = openModule(); });
    return module;
}

// One of the module's checks (`asked`), its refusal as `code`; Ok when there is no module and none is required (a
// unit test's binary has none beside it).
template<class Function, class... Arguments>
Status askModule(Function Module::*asked, ErrorCode code, Arguments... arguments)
{
    const Module &module = theModule();
    if (module.*asked == nullptr && moduleRequired)
        return makeError(ErrorCode::NotFound, module.error);
    if (module.*asked == nullptr)
        return Ok{};
    std::string error;
    if (!(module.*asked)(arguments..., &error))
        return makeError(code, error);
    return Ok{};
}

} // namespace

bool streamBuiltIn()
{
    return true;
}

Result<std::unique_ptr<EncodedStreamEngine>> loadStreamEngine(const StreamOptions &options, const EngineLog &log)
{
    const Module &module = theModule();
    if (module.create == nullptr || module.check == nullptr)
        return makeError(ErrorCode::NotFound, module.error);
    std::string error;
    EncodedStreamEngine *engine = module.create(&options, &log, &error);
    if (engine == nullptr)
        return makeError(ErrorCode::Unsupported, error);
    return std::unique_ptr<EncodedStreamEngine>(engine);
}

Status checkEncoder(const EncoderOptions &options)
{
    return askModule(&Module::check, ErrorCode::NotFound, &options);
}

Status checkRtspsCertificate(const std::string &certPem, const std::string &keyPem)
{
    return askModule(&Module::checkTls, ErrorCode::Unsupported, &certPem, &keyPem);
}

void requireStreamModule()
{
    moduleRequired = true;
}

} // namespace overlayd
