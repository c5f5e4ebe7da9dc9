#!/usr/bin/env python3
"""The include-direction check (CTest structure.includes): every #include "..." of a source file
must name a header of its own folder or of a folder its layer may depend on (layers.txt, written
by cmake/Layers.cmake from CMakeLists.txt), and only the folders marked VULKAN may include Vulkan,
GLFW or ImGui's backends. Prints one line per violation and exits 1 when there is any."""
import os
import re
import sys

VULKAN = re.compile(r'#\s*include\s*[<"](vulkan/|GLFW/|imgui_impl_)')
LOCAL = re.compile(r'#\s*include\s*"([^"]+)"')
SHARED = ("shaders/",)  # the C++/GLSL shared headers: every layer may include them


def main(root, table_path):
    layers = []
    for line in open(table_path):
        if line.startswith("#") or not line.strip():
            continue
        folder, vk, allowed = line.rstrip("\n").split("|")
        layers.append((folder, vk == "yes", allowed.split()))
    layers.sort(key=lambda l: -len(l[0]))  # the longest folder a file is in decides

    def layer_of(path):
        for folder, vk, allowed in layers:
            if path.startswith(folder + "/") and "/" not in path[len(folder) + 1:]:
                return folder, vk, allowed
        return None

    def folder_of(path):
        return os.path.dirname(path)

    problems = []
    checked = 0
    for top in ("renderer", "views", "app"):
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in files:
                if not name.endswith((".h", ".cpp")):
                    continue
                rel = os.path.relpath(os.path.join(dirpath, name), root)
                layer = layer_of(rel)
                if layer is None:
                    problems.append(f"{rel}: in no layer of CMakeLists.txt (add its folder with gblens_layer)")
                    continue
                folder, vk, allowed = layer
                checked += 1
                for n, text in enumerate(open(os.path.join(root, rel), errors="replace"), 1):
                    if VULKAN.search(text) and not vk:
                        problems.append(f"{rel}:{n}: {folder}/ may not include Vulkan, GLFW or ImGui backends: {text.strip()}")
                    m = LOCAL.search(text)
                    if not m:
                        continue
                    inc = m.group(1)
                    if inc.startswith(SHARED) or "/" not in inc:
                        continue  # shaders/ headers; generated headers and siblings by bare name
                    if folder_of(inc) not in allowed:
                        problems.append(f"{rel}:{n}: {folder}/ may not include {inc} "
                                        f"(allowed: {', '.join(a + '/' for a in allowed)})")
    for p in problems:
        print(p)
    print(f"check_includes: {checked} files, {len(problems)} violation(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
