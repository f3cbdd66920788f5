// Linked into vkray and vkray_tests in sanitizer builds only (see the
// Reliability block of CMakeLists.txt). Lavapipe leaks a few JIT objects that
// it never frees (Mesa 22.3); by the time LeakSanitizer reports them at exit,
// the Vulkan loader has unloaded lavapipe, so their frames read "<unknown
// module>" and no suppression can name them. Loading the loader, lavapipe
// and the validation layer once more with RTLD_NODELETE keeps them mapped, so
// the report names libvulkan_lvp.so and scripts/lsan.supp can suppress
// exactly that library. Nothing else changes: the loader still loads and
// initialises them as always (dlopen of a loaded library returns it as is).
#include <dlfcn.h>

#include <initializer_list>

namespace {

__attribute__((constructor)) void pinVulkanLibraries() {
    for (const char* library :
         {"libvulkan.so.1", "libvulkan_lvp.so", "libVkLayer_khronos_validation.so"})
        ::dlopen(library, RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE);  // absent: nothing to pin
}

}  // namespace
