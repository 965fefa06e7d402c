#!/usr/bin/env python3
"""Set-up is complete: scripts/debian-packages.txt, the one list scripts/setup.sh installs, covers
every external dependency the repository has. Scans the tree (no network, nothing imported or run
from what it finds, about a second) and resolves each dependency through the tables below:

  - every find_package / find_program / pkg_check_modules of every CMakeLists.txt and *.cmake, the
    compiler of project(LANGUAGES ...) and the programs of COMMAND lines;
  - every #include <...> of the C++ sources that is not the standard library's;
  - every import of every python file (ast), of python run from shell (heredocs, python3 -c,
    python3 -m) and of python in C++ strings ({"-c", "import matplotlib"});
  - every program the shell scripts (*.sh, .ci/run), python (subprocess, shutil.which) and C++
    (posix_spawn, runProcess, runProgram, std::system, popen, onPath) call;
  - runtime components named in C++ strings (the validation layer).

Each must resolve to a package of the list, to the Python standard library, to a base-system
program (an Essential or Priority: required package, on every Debian system), to something this
repository builds or holds, or to an entry of NOT_FROM_DEBIAN (each with its reason and where it is
installed). The converse holds too: every listed package is needed by something found, or is in
INFRASTRUCTURE with its reason, and every line says what uses it.

  setup_completeness_test.py REPO                   the check (ctest: Setup.DebianPackageListComplete)
  setup_completeness_test.py REPO --self-test       feeds a fake tree with omissions of every kind and
                                                    checks each is reported (Setup.GuardReportsOmissions)
  setup_completeness_test.py REPO --verify-machine  checks the tables against this machine: dpkg -S on
                                                    each table row's file, apt-cache knows every listed
                                                    package (Setup.TablesMatchDpkg; exit 77 = skipped
                                                    where there is no dpkg)
  setup_completeness_test.py REPO --list            prints every dependency found and what provides it

Python's own `python3` may be a pyenv shim that cannot see Debian's modules: nothing here depends
on what is importable, only on the lists and tables.
"""
import ast
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

PACKAGE_LIST = "scripts/debian-packages.txt"
THIS_FILE = "tests/setup/setup_completeness_test.py"

# ---- Tables: a dependency -> the packages of the list that provide it, each with the file through
# which it is found (checked with dpkg -S by --verify-machine; `*` matches the multiarch triplet).
# A row may name more than one package when one alone does not work.

# find_package(NAME) and find_package(NAME COMPONENTS C) (key "NAME/C").
CMAKE_PACKAGES = {
    "Vulkan": [("libvulkan-dev", "/usr/lib/*/libvulkan.so")],
    "Vulkan/glslangValidator": [("glslang-tools", "/usr/bin/glslangValidator")],
    "glm": [("libglm-dev", "/usr/share/cmake/glm/glmConfig.cmake")],
    "TinyGLTF": [("libtinygltf-dev", "/usr/lib/*/cmake/TinyGLTF/TinyGLTFConfig.cmake"),
                 ("nlohmann-json3-dev", "/usr/include/nlohmann/json.hpp")],  # tiny_gltf.h includes it
    "OpenEXR": [("libopenexr-dev", "/usr/lib/*/cmake/OpenEXR/OpenEXRConfig.cmake")],
    "CLI11": [("libcli11-dev", "/usr/share/cmake/CLI11/CLI11Config.cmake")],
    "pugixml": [("libpugixml-dev", "/usr/lib/*/cmake/pugixml/pugixml-config.cmake")],
    "JPEG": [("libjpeg-dev", "/usr/include/jpeglib.h")],
    "Threads": [("build-essential", "/usr/include/pthread.h")],
    "glfw3": [("libglfw3-dev", "/usr/lib/*/cmake/glfw3/glfw3Config.cmake")],
    "GTest": [("libgtest-dev", "/usr/lib/*/cmake/GTest/GTestConfig.cmake")],
    "Python3": [("python3", "/usr/bin/python3")],
    "Python3/Interpreter": [("python3", "/usr/bin/python3")],
    "SPIRV-Tools": [("spirv-tools", "/usr/lib/*/cmake/SPIRV-Tools/SPIRV-ToolsConfig.cmake")],
    "SPIRV-Tools-opt": [("spirv-tools", "/usr/lib/*/cmake/SPIRV-Tools-opt/SPIRV-Tools-optConfig.cmake")],
}
# pkg_check_modules(PREFIX module...) modules, and find_library / find_path names.
PKG_CONFIG_MODULES = {}
CMAKE_LIBRARIES = {}
# project(... LANGUAGES L): the compiler.
CMAKE_LANGUAGES = {
    "CXX": [("build-essential", "/usr/bin/g++")],
    "C": [("build-essential", "/usr/bin/gcc")],
}

# #include <...> outside the C++ standard library: a path prefix (a folder or a file name).
HEADERS = {
    "vulkan/": [("libvulkan-dev", "/usr/include/vulkan/vulkan.h")],
    "glm/": [("libglm-dev", "/usr/include/glm/glm.hpp")],
    "tiny_gltf.h": [("libtinygltf-dev", "/usr/include/tiny_gltf.h"),
                    ("nlohmann-json3-dev", "/usr/include/nlohmann/json.hpp")],
    "nlohmann/": [("nlohmann-json3-dev", "/usr/include/nlohmann/json.hpp")],
    "stb/": [("libstb-dev", "/usr/include/stb/stb_image.h")],
    "Imf": [("libopenexr-dev", "/usr/include/OpenEXR/ImfHeader.h")],
    "Iex": [("libopenexr-dev", "/usr/include/OpenEXR/Iex.h")],
    "half.h": [("libopenexr-dev", "/usr/include/Imath/half.h")],  # Imath's, through libopenexr-dev
    "CLI/": [("libcli11-dev", "/usr/include/CLI/CLI.hpp")],
    "pugixml.hpp": [("libpugixml-dev", "/usr/include/pugixml.hpp")],
    "jpeglib.h": [("libjpeg-dev", "/usr/include/jpeglib.h")],
    "GLFW/": [("libglfw3-dev", "/usr/include/GLFW/glfw3.h")],
    "gtest/": [("libgtest-dev", "/usr/include/gtest/gtest.h")],
    "spirv-tools/": [("spirv-tools", "/usr/include/spirv-tools/optimizer.hpp")],
    # The C library (POSIX) and the compiler's intrinsics: build-essential (libc6-dev, gcc).
    "sys/": [("build-essential", "/usr/include/spawn.h")],
    "spawn.h": [("build-essential", "/usr/include/spawn.h")],
    "unistd.h": [("build-essential", "/usr/include/unistd.h")],
    "fcntl.h": [("build-essential", "/usr/include/fcntl.h")],
    "signal.h": [("build-essential", "/usr/include/signal.h")],
    "sched.h": [("build-essential", "/usr/include/sched.h")],
    "pthread.h": [("build-essential", "/usr/include/pthread.h")],
    "dirent.h": [("build-essential", "/usr/include/dirent.h")],
    "poll.h": [("build-essential", "/usr/include/poll.h")],
    "dlfcn.h": [("build-essential", "/usr/include/dlfcn.h")],
    "errno.h": [("build-essential", "/usr/include/errno.h")],
    "emmintrin.h": [("build-essential", "/usr/lib/gcc/x86_64-linux-gnu/*/include/emmintrin.h")],
    "immintrin.h": [("build-essential", "/usr/lib/gcc/x86_64-linux-gnu/*/include/immintrin.h")],
    "xmmintrin.h": [("build-essential", "/usr/lib/gcc/x86_64-linux-gnu/*/include/xmmintrin.h")],
}
STD_CXX_HEADERS = set("""
algorithm any array atomic barrier bit bitset cassert cctype cerrno cfenv cfloat charconv chrono cinttypes
climits clocale cmath codecvt compare complex concepts condition_variable coroutine csetjmp csignal cstdarg
cstddef cstdint cstdio cstdlib cstring ctime cuchar cwchar cwctype deque exception execution expected
filesystem format forward_list fstream functional future initializer_list iomanip ios iosfwd iostream
istream iterator latch limits list locale map memory memory_resource mutex new numbers numeric optional
ostream queue random ranges ratio regex scoped_allocator semaphore set shared_mutex source_location span
sstream stack stdexcept stop_token streambuf string string_view syncstream system_error thread tuple
type_traits typeindex typeinfo unordered_map unordered_set utility valarray variant vector version
assert.h stdint.h stdio.h stdlib.h string.h math.h limits.h float.h stddef.h stdarg.h time.h ctype.h
""".split())

# Python modules Debian ships outside python3 (including the standard library parts it splits out).
PYTHON_MODULES = {
    "matplotlib": [("python3-matplotlib", "/usr/lib/python3/dist-packages/matplotlib/__init__.py")],
    "numpy": [("python3-numpy", "/usr/lib/python3/dist-packages/numpy/__init__.py")],
    "PIL": [("python3-pil", "/usr/lib/python3/dist-packages/PIL/__init__.py")],
    "venv": [("python3-venv", "/usr/lib/python3.*/ensurepip/__init__.py")],  # python3 -m venv needs ensurepip
    "ensurepip": [("python3-venv", "/usr/lib/python3.*/ensurepip/__init__.py")],
    "tkinter": [("python3-tk", "/usr/lib/python3.*/tkinter/__init__.py")],
    "distutils": [("python3-distutils", "/usr/lib/python3.*/distutils/__init__.py")],
    "lib2to3": [("python3-lib2to3", "/usr/lib/python3.*/lib2to3/__init__.py")],
}

# Programs (checked with dpkg -S on /usr/bin/NAME).
PROGRAMS = {
    "cmake": [("cmake", "/usr/bin/cmake")],
    "ctest": [("cmake", "/usr/bin/ctest")],
    "ninja": [("ninja-build", "/usr/bin/ninja")],
    "c++": [("build-essential", "/usr/bin/g++")],
    "g++": [("build-essential", "/usr/bin/g++")],
    "gcc": [("build-essential", "/usr/bin/gcc")],
    "make": [("build-essential", "/usr/bin/make")],
    "git": [("git", "/usr/bin/git")],
    "glslangValidator": [("glslang-tools", "/usr/bin/glslangValidator")],
    "spirv-val": [("spirv-tools", "/usr/bin/spirv-val")],
    "spirv-opt": [("spirv-tools", "/usr/bin/spirv-opt")],
    "spirv-dis": [("spirv-tools", "/usr/bin/spirv-dis")],
    "vulkaninfo": [("vulkan-tools", "/usr/bin/vulkaninfo")],
    "clang-format": [("clang-format", "/usr/bin/clang-format")],
    "clang": [("clang", "/usr/bin/clang")],
    "clang++": [("clang", "/usr/bin/clang++")],
    "Xvfb": [("xvfb", "/usr/bin/Xvfb")],
    "xvfb-run": [("xvfb", "/usr/bin/xvfb-run"), ("xauth", "/usr/bin/xauth")],  # xvfb-run calls xauth
    "xauth": [("xauth", "/usr/bin/xauth")],
    "python3": [("python3", "/usr/bin/python3")],
    "python": [("python-is-python3", "/usr/bin/python")],  # Debian's python3 has no `python`
}
# Programs of the base system: an Essential or Priority: required package, on every Debian system
# (--verify-machine checks the package's Essential / Priority field).
BASE_PROGRAMS = {
    "coreutils": """cat head tail mktemp rm mkdir rmdir cut tr sort uniq seq date realpath basename dirname
        nproc tee sleep id env printf echo wc cp mv ln ls touch chmod stat du df timeout true false
        readlink yes nice stdbuf sha256sum md5sum install test expr""",
    "grep": "grep egrep fgrep",
    "sed": "sed",
    "mawk": "awk mawk",
    "findutils": "find xargs",
    "diffutils": "cmp diff",
    "bash": "bash",
    "dash": "sh",
    "tar": "tar",
    "gzip": "gzip gunzip zcat",
    "util-linux": "flock taskset setsid",
    "dpkg": "dpkg dpkg-query dpkg-deb",
    "apt": "apt-get apt-cache apt",
    "hostname": "hostname",
}
BASE_PROGRAM_PACKAGE = {p: pkg for pkg, names in BASE_PROGRAMS.items() for p in names.split()}

# Runtime components found by name in C++ strings.
RUNTIME_STRINGS = {
    "VK_LAYER_KHRONOS_validation": [("vulkan-validationlayers",
                                     "/usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json")],
}

# Listed packages nothing in the tree names, each with the reason it is listed.
INFRASTRUCTURE = {
    "mesa-vulkan-drivers": ("lavapipe, the Vulkan device CI and the tests render on (no code names it)",
                            "/usr/share/vulkan/icd.d/lvp_icd.json"),
    "vulkan-tools": ("vulkaninfo, to inspect the Vulkan devices by hand when `pt devices` lists none",
                     "/usr/bin/vulkaninfo"),
    "libclang-rt-14-dev": ("clang's ASan, UBSan and libFuzzer runtimes (-fsanitize=... in CMakeLists.txt, "
                           "scripts/sanitizers.sh)", "/usr/lib/llvm-14/lib/clang/14*/lib/linux/libclang_rt.asan-x86_64.a"),
}

# Dependencies that do not come from a Debian package, each with the reason and where it comes from.
NOT_FROM_DEBIAN = {
    "program:sudo": "scripts/setup.sh and scripts/setup_ray_venv.sh run apt-get and pip through sudo "
                    "when not run as root; it cannot install itself (Debian installs it with an "
                    "administrator account)",
    "python:ray": "Ray 2.60.0 from PyPI, in the venv /opt/pt-ray that scripts/setup_ray_venv.sh makes "
                  "(setup.sh calls it): tools/pt_ray and its tests (tests/app/ray_test.cpp)",
    "python:OpenEXR": "the OpenEXR bindings from PyPI (pip install OpenEXR; Debian 12 has none): only the "
                      "benchmarks run by hand, bench/course_exr_compare.py, bench/bench_vs_mitsuba.py and "
                      "bench/make_mitsuba_reference.py (whose venv scripts/setup_mitsuba_venv.sh installs them)",
    "python:mitsuba": "Mitsuba 3 from PyPI, in the venv /opt/mitsuba that scripts/setup_mitsuba_venv.sh makes (not "
                      "part of setup.sh): only bench/bench_vs_mitsuba.py and bench/make_mitsuba_reference.py, run by "
                      "hand",
}

SHELL_KEYWORDS = set("""if then else elif fi do done while until for in case esac function select time !
    { } [[ ]] coproc""".split())
SHELL_BUILTINS = set("""echo printf read local export cd set unset exit return shift wait kill trap
    mapfile readarray declare typeset source . true false test [ eval exec command builtin type hash
    pushd popd dirs let ulimit umask getopts break continue alias unalias shopt caller enable help
    history jobs fg bg disown suspend times compgen complete logout pwd""".split())
SHELL_PREFIXES = {"$SUDO", "${SUDO}", "sudo", "env", "exec", "nohup", "time", "nice", "timeout", "stdbuf"}
CXX_SPAWN_CALLS = ("runProcess", "runProgram", "runPython", "posix_spawnp", "posix_spawn", "execvp", "execv",
                   "execlp", "execl", "system", "popen", "onPath")
PY_SPAWN_ATTRS = {"run", "call", "check_call", "check_output", "Popen", "getoutput", "getstatusoutput"}
PY_SHELL_CALLS = {"system", "popen"}


# ---- The package list ----------------------------------------------------------------------------

def read_package_list(path):
    """[(package, line number, comment)] of the list; comment is "" when the line has none."""
    entries = []
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            text, _, comment = line.partition("#")
            words = text.split()
            if not words:
                continue
            for w in words:  # several on a line: each is reported for its missing reason
                entries.append((w, number, comment.strip() if len(words) == 1 else ""))
    return entries


# ---- Walking the tree --------------------------------------------------------------------------

SKIP_DIRS = {".git", "__pycache__", "node_modules", ".venv", "venv", "out"}
SKIP_PATHS = ("tests/data/", "tests/fuzz/corpus/", "tests/references/", "scenes/", "bench/images/")


def tree_files(repo):
    """Relative paths of the tree's files: git's tracked and untracked-but-not-ignored files when the
    repository is a git work tree, else a walk that skips build folders."""
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "-co", "--exclude-standard"], capture_output=True,
                             text=True, timeout=30)
        if out.returncode == 0 and out.stdout.strip():
            return sorted(p for p in out.stdout.splitlines() if os.path.isfile(os.path.join(repo, p)))
    except (OSError, subprocess.SubprocessError):
        pass
    files = []
    for root, dirs, names in os.walk(repo):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")
                   and not os.path.exists(os.path.join(root, d, "CMakeCache.txt"))]
        for n in names:
            files.append(os.path.relpath(os.path.join(root, n), repo))
    return sorted(files)


def first_line(path):
    try:
        with open(path, "rb") as f:
            return f.readline(200).decode("utf-8", "replace")
    except OSError:
        return ""


def classify(repo, files):
    kinds = {"cmake": [], "cxx": [], "python": [], "shell": []}
    for rel in files:
        name = os.path.basename(rel)
        if name == "CMakeLists.txt" or name.endswith(".cmake"):
            kinds["cmake"].append(rel)
            continue
        data_file = rel.startswith(SKIP_PATHS)
        if rel.endswith((".cpp", ".h", ".hpp", ".cc", ".cpp.in", ".h.in")):
            if not data_file:
                kinds["cxx"].append(rel)
        elif rel.endswith(".py"):
            kinds["python"].append(rel)
        elif rel.endswith((".sh", ".bash", ".sbatch")):
            kinds["shell"].append(rel)
        elif not data_file and "." not in name:
            shebang = first_line(os.path.join(repo, rel))
            if shebang.startswith("#!"):
                if "python" in shebang:
                    kinds["python"].append(rel)
                elif re.search(r"\b(ba)?sh\b", shebang):
                    kinds["shell"].append(rel)
    return kinds


def read(repo, rel):
    with open(os.path.join(repo, rel), encoding="utf-8", errors="replace") as f:
        return f.read()


# ---- Findings ------------------------------------------------------------------------------------

class Needs:
    """What the tree needs: (kind, name) -> first place it is needed ("file:line")."""

    def __init__(self):
        self.items = {}

    def add(self, kind, name, where):
        self.items.setdefault((kind, name), where)


def line_of(text, index):
    return text.count("\n", 0, index) + 1


# ---- CMake ---------------------------------------------------------------------------------------

CMAKE_KEYWORDS = {"REQUIRED", "QUIET", "CONFIG", "MODULE", "NO_MODULE", "EXACT", "GLOBAL", "COMPONENTS",
                  "OPTIONAL_COMPONENTS", "NO_POLICY_SCOPE", "NAMES", "PATHS", "HINTS", "PATH_SUFFIXES",
                  "DOC", "NO_DEFAULT_PATH", "IMPORTED_TARGET"}


def strip_cmake_comments(text):
    return re.sub(r"#[^\n]*", lambda m: " " * len(m.group(0)), text)


def scan_cmake(repo, files, needs, project_targets):
    for rel in files:
        text = strip_cmake_comments(read(repo, rel))
        for m in re.finditer(r"\b(find_package|find_program|find_library|find_path|pkg_check_modules|"
                             r"pkg_search_module|project)\s*\(([^)]*)\)", text, re.IGNORECASE):
            command, args = m.group(1).lower(), m.group(2).split()
            where = f"{rel}:{line_of(text, m.start())}"
            if not args:
                continue
            if command == "find_package":
                needs.add("cmake", args[0], where)
                components, collecting = [], False
                for a in args[1:]:
                    if a in ("COMPONENTS", "OPTIONAL_COMPONENTS", "REQUIRED"):
                        collecting = True  # find_package(X REQUIRED a b) names components too
                    elif a in CMAKE_KEYWORDS:
                        collecting = False
                    elif collecting:
                        components.append(a)
                for c in components:
                    needs.add("cmake", f"{args[0]}/{c}", where)
            elif command == "find_program":
                names = args[2:] if len(args) > 2 and args[1] == "NAMES" else args[1:2]
                for n in names:
                    if n in CMAKE_KEYWORDS:
                        break
                    needs.add("program", n, where)
            elif command in ("find_library", "find_path"):
                names = args[2:] if len(args) > 2 and args[1] == "NAMES" else args[1:2]
                for n in names:
                    if n in CMAKE_KEYWORDS:
                        break
                    needs.add("cmake-library", n, where)
            elif command in ("pkg_check_modules", "pkg_search_module"):
                needs.add("program", "pkg-config", where)
                for n in args[1:]:
                    if n not in CMAKE_KEYWORDS:
                        needs.add("pkg-config", re.split(r"[<>=]", n)[0], where)
            elif command == "project":
                if "LANGUAGES" in args:
                    for lang in args[args.index("LANGUAGES") + 1:]:
                        if lang in ("VERSION", "DESCRIPTION", "HOMEPAGE_URL"):
                            break
                        needs.add("language", lang, where)
                else:
                    needs.add("language", "CXX", where)  # CMake's default: C and C++
                    needs.add("language", "C", where)
        for m in re.finditer(r"\bCOMMAND\s+(\S+)", text):
            word = m.group(1).strip('"')
            if "::" in word or word.startswith(("$", "-")) or word in project_targets:
                continue
            needs.add("program", os.path.basename(word), f"{rel}:{line_of(text, m.start())}")
        if re.search(r"-G\s*Ninja|CMAKE_GENERATOR\s+\"?Ninja", text):
            needs.add("program", "ninja", f"{rel}:1")


def cmake_targets(repo, files):
    """add_executable names of the tree (its own programs); ${...} parts match anything."""
    names = set()
    for rel in files:
        for m in re.finditer(r"\badd_executable\s*\(\s*([^\s)]+)", read(repo, rel)):
            names.add(m.group(1))
    return names


def is_project_program(name, targets):
    for t in targets:
        pattern = "^" + re.sub(r"\\\$\\\{[^}]*\\\}", ".+", re.escape(t)) + "$"
        if re.match(pattern, name):
            return True
    return False


# ---- Python --------------------------------------------------------------------------------------

def python_imports(source, where, needs, prefix_line=0):
    """Adds the top-level modules `source` imports; falls back to a regex when it does not parse
    (a snippet with shell substitutions in it)."""
    try:
        tree = ast.parse(source)
    except SyntaxError:
        for m in re.finditer(r"(?:^|[;\n])\s*(?:import\s+([\w., ]+)|from\s+(\w+)[\w.]*\s+import)", source):
            names = [m.group(2)] if m.group(2) else [n.strip().split(".")[0] for n in m.group(1).split(",")]
            for n in names:
                if n:
                    needs.add("python", n.split()[0], where(line_of(source, m.start()) + prefix_line))
        return None
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                needs.add("python", alias.name.split(".")[0], where(node.lineno + prefix_line))
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            needs.add("python", node.module.split(".")[0], where(node.lineno + prefix_line))
    return tree


def dotted(node):
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
    return ".".join(reversed(parts))


def scan_python(repo, files, needs):
    for rel in files:
        source = read(repo, rel)
        tree = python_imports(source, lambda n, rel=rel: f"{rel}:{n}", needs)
        if tree is None:
            continue
        from_subprocess = re.search(r"^\s*from\s+subprocess\s+import", source, re.MULTILINE) is not None
        for node in ast.walk(tree):
            if not isinstance(node, ast.Call) or not node.args:
                continue
            name = dotted(node.func)
            last = name.split(".")[-1]
            first = node.args[0]
            where = f"{rel}:{node.lineno}"
            shell = any(k.arg == "shell" and isinstance(k.value, ast.Constant) and k.value.value for k in node.keywords)
            if (name.startswith("os.") and last in PY_SHELL_CALLS) or (last in PY_SPAWN_ATTRS and shell):
                if isinstance(first, ast.Constant) and isinstance(first.value, str):
                    scan_shell_text(first.value, rel, needs, set(), node.lineno)
            elif (name.startswith("subprocess.") and last in PY_SPAWN_ATTRS) or (name in PY_SPAWN_ATTRS and
                                                                                 from_subprocess) or \
                    re.match(r"os\.(exec|spawn)", name) or name == "shutil.which":
                arg = first.elts[0] if isinstance(first, (ast.List, ast.Tuple)) and first.elts else first
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and arg.value.split():
                    add_program(arg.value.split()[0], where, needs)


# ---- Shell ---------------------------------------------------------------------------------------

class ShellWord:
    def __init__(self, text, quoted, line):
        self.text, self.quoted, self.line = text, quoted, line


def split_heredocs(text):
    """The text with heredoc bodies blanked (line numbers kept), and [(command line, body, first
    body line number)]."""
    lines = text.split("\n")
    out, docs, i = [], [], 0
    while i < len(lines):
        line = lines[i]
        out.append(line)
        m = re.search(r"(?<!<)<<(?!<)(-?)\s*(['\"]?)(\w+)\2", line)
        i += 1
        if m:
            body, start = [], i + 1
            while i < len(lines) and (lines[i].strip() if m.group(1) else lines[i]) != m.group(3):
                body.append(lines[i])
                out.append("")
                i += 1
            if i < len(lines):
                out.append("")
                i += 1
            docs.append((line, "\n".join(body), start))
    return "\n".join(out), docs


def tokenize_shell(text, line0=1):
    """Simple commands of a shell text: [[ShellWord]]; command substitutions and subshells become
    commands of their own. A sketch of the shell's grammar, enough for scripts written plainly."""
    commands, current = [], []
    word, quoted, word_line = None, False, line0
    line = line0
    i, n = 0, len(text)

    def finish_word():
        nonlocal word, quoted
        if word is not None:
            current.append(ShellWord(word, quoted, word_line))
        word, quoted = None, False

    def finish_command():
        nonlocal current
        finish_word()
        if current:
            commands.append(current)
        current = []

    def append(s):
        nonlocal word, word_line
        if word is None:
            word, word_line = "", line
        word += s

    def matching(start, open_char, close_char):
        """Index just past the close matching text[start] == open_char, skipping quotes."""
        depth, j = 0, start
        while j < n:
            c = text[j]
            if c == "\\":
                j += 2
                continue
            if c == "'" and open_char != "{":
                k = text.find("'", j + 1)
                j = n if k < 0 else k + 1
                continue
            if c == '"':
                j = skip_double(j)
                continue
            if c == open_char:
                depth += 1
            elif c == close_char:
                depth -= 1
                if depth == 0:
                    return j + 1
            j += 1
        return n

    def skip_double(j):
        """Index past the double-quoted string at j; its command substitutions are tokenized."""
        j += 1
        while j < n and text[j] != '"':
            if text[j] == "\\":
                j += 2
                continue
            if text.startswith("$((", j):
                j = matching(j + 1, "(", ")")
                continue
            if text.startswith("$(", j):
                end = matching(j + 1, "(", ")")
                commands.extend(tokenize_shell(text[j + 2:end - 1], line0 + text.count("\n", 0, j)))
                j = end
                continue
            if text[j] == "`":
                k = text.find("`", j + 1)
                k = n if k < 0 else k
                commands.extend(tokenize_shell(text[j + 1:k], line0 + text.count("\n", 0, j)))
                j = k + 1
                continue
            j += 1
        return j + 1

    while i < n:
        c = text[i]
        if c == "\\" and i + 1 < n:
            if text[i + 1] == "\n":
                line += 1
                i += 2
                continue
            append(text[i + 1])
            i += 2
            continue
        if c == "\n":
            finish_command()
            line += 1
            i += 1
            continue
        if c in " \t":
            finish_word()
            i += 1
            continue
        if c == "#" and word is None:
            k = text.find("\n", i)
            i = n if k < 0 else k
            continue
        if c == "'":
            k = text.find("'", i + 1)
            k = n if k < 0 else k
            append(text[i + 1:k])
            quoted = True
            line += text.count("\n", i, k)
            i = k + 1
            continue
        if c == '"':
            end = skip_double(i)
            append(text[i + 1:end - 1])
            quoted = True
            line += text.count("\n", i, end)
            i = end
            continue
        if text.startswith("$((", i) or text.startswith("((", i) and word is None:
            end = matching(i + (1 if c == "$" else 0), "(", ")")
            append(text[i:end])
            line += text.count("\n", i, end)
            i = end
            continue
        if text.startswith("$(", i) or text.startswith("<(", i) or text.startswith(">(", i):
            end = matching(i + 1, "(", ")")
            commands.extend(tokenize_shell(text[i + 2:end - 1], line))
            append("$(...)")
            line += text.count("\n", i, end)
            i = end
            continue
        if text.startswith("${", i):
            end = matching(i + 1, "{", "}")
            append(text[i:end])
            i = end
            continue
        if c == "`":
            k = text.find("`", i + 1)
            k = n if k < 0 else k
            commands.extend(tokenize_shell(text[i + 1:k], line))
            append("$(...)")
            i = k + 1
            continue
        if c == "(" and word is not None and word.endswith("="):
            end = matching(i, "(", ")")  # an array assignment: name=(a b c)
            append(text[i:end])
            line += text.count("\n", i, end)
            i = end
            continue
        if c in "|&;()":
            finish_command()
            i += 1
            continue
        if c in "<>":
            finish_word()
            j = i
            while j < n and text[j] in "<>&":
                j += 1
            while j < n and text[j].isdigit():
                j += 1
            current.append(ShellWord(text[i:j], False, line))  # a redirection; its target follows
            i = j
            continue
        append(c)
        i += 1
    finish_command()
    return commands


ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*(\[[^\]]*\])?\+?=")


def program_name(word):
    """A program word as the table knows it: /usr/bin/python3 -> python3; None for a path into the
    tree (./build/pt, "$build/tests/x"), a variable or a substitution."""
    if not word or word.startswith(("$", "./", "../", "~")) or "$" in word:
        return None
    if "/" in word:
        return os.path.basename(word) if word.startswith(("/usr/", "/bin/", "/sbin/")) else None
    return word


def scan_shell_text(text, rel, needs, functions, line0=1):
    text, heredocs = split_heredocs(text)
    for command_line, body, start in heredocs:
        if re.search(r"\bpython[0-9.]*\"?\s+-", command_line):
            python_imports(body, lambda k: f"{rel}:{k}", needs, start - 1 + line0 - 1)
    for words in tokenize_shell(text, line0):
        scan_shell_command(words, rel, needs, functions)


def scan_shell_command(words, rel, needs, functions):
    # Redirection targets are not words of the command.
    plain, skip = [], False
    for w in words:
        if skip:
            skip = False
            continue
        if not w.quoted and re.match(r"^[0-9]*[<>]", w.text):
            skip = not re.search(r"&[0-9-]$", w.text)
            continue
        plain.append(w)
    i = 0
    while i < len(plain):
        w = plain[i]
        t = w.text
        if not w.quoted and (t in SHELL_KEYWORDS or ASSIGNMENT.match(t)):
            if t in ("for", "case", "select"):
                return
            if t == "[[":
                while i < len(plain) and plain[i].text != "]]":
                    i += 1
            i += 1
            continue
        if t in SHELL_PREFIXES:  # a program that runs the next word: sudo, env, timeout 10 ...
            if t not in ("exec", "time"):
                needs.add("program", "sudo" if "SUDO" in t else t, f"{rel}:{w.line}")
            i += 1
            while i < len(plain) and (plain[i].text.startswith("-") or ASSIGNMENT.match(plain[i].text)):
                i += 1
            if t == "timeout" and i < len(plain):
                i += 1  # the duration
            continue
        break
    if i >= len(plain):
        return
    head = plain[i]
    args = [w.text for w in plain[i + 1:]]
    where = f"{rel}:{head.line}"
    # Python run from here: python3 -c "...", python3 -m module (also a venv's python given by variable).
    if re.search(r"(^|/)python[0-9.]*$", head.text):
        for k, a in enumerate(args[:-1]):
            if a == "-c":
                python_imports(args[k + 1], lambda _: where, needs)
                break
            if a == "-m":
                needs.add("python", args[k + 1].split(".")[0], where)
                break
    if head.text == "command" and args[:1] == ["-v"]:
        for a in args[1:]:
            if program_name(a):
                needs.add("program", program_name(a), where)
        return
    if head.text in SHELL_BUILTINS or head.text in functions or head.text == "$(...)":
        return
    name = program_name(head.text)
    if name is None or not re.match(r"^[A-Za-z0-9_.+-]+$", name):
        return
    needs.add("program", name, where)
    # cmake -G Ninja (and the generator of ctest/cmake --build): the generator's program.
    if name == "cmake" and "-G" in args and args[args.index("-G") + 1:args.index("-G") + 2] == ["Ninja"]:
        needs.add("program", "ninja", where)


def shell_functions(text):
    return set(re.findall(r"^\s*(?:function\s+)?([A-Za-z_][\w-]*)\s*\(\)", text, re.MULTILINE))


def scan_shell(repo, files, needs):
    for rel in files:
        text = read(repo, rel)
        scan_shell_text(text, rel, needs, shell_functions(text))


# ---- C++ -----------------------------------------------------------------------------------------

CXX_STRING = re.compile(r'"((?:[^"\\\n]|\\.)*)"')


def scan_cxx(repo, files, needs):
    for rel in files:
        text = read(repo, rel)
        for m in re.finditer(r"^\s*#\s*include\s*<([^>]+)>", text, re.MULTILINE):
            needs.add("header", m.group(1), f"{rel}:{line_of(text, m.start())}")
        for m in CXX_STRING.finditer(text):
            s, where = m.group(1), f"{rel}:{line_of(text, m.start())}"
            if re.match(r"^\s*(import\s+[A-Za-z_]|from\s+[A-Za-z_][\w.]*\s+import\b)", s):
                python_imports(s.replace("\\n", "\n"), lambda _, where=where: where, needs)
            for key in RUNTIME_STRINGS:
                if key in s:
                    needs.add("runtime", key, where)
        spawns = re.search(r"\b(" + "|".join(CXX_SPAWN_CALLS) + r")\s*\(", text)
        if not spawns:
            continue
        calls = "|".join(CXX_SPAWN_CALLS)
        # system("...") / popen("..."): a shell command line.
        for m in re.finditer(r"\b(?:std::)?(?:system|popen)\s*\(\s*\"((?:[^\"\\\n]|\\.)*)\"", text):
            scan_shell_text(m.group(1), rel, needs, set(), line_of(text, m.start()))
        # SPAWN("prog" ...), SPAWN(x, {"prog", ...}) and SPAWN({"prog", ...}).
        for m in re.finditer(r"\b(?:" + calls + r")\s*\(\s*(?:[^,(){}\"]*,\s*)?\{?\s*\"([^\"]+)\"", text):
            if not re.search(r"\b(?:std::)?(?:system|popen)\s*\(\s*\"", m.group(0)):
                add_program(m.group(1), f"{rel}:{line_of(text, m.start())}", needs)
        # std::vector<std::string> cmd = {"prog", ...}: an argv handed to one of the calls above.
        for m in re.finditer(r"std::vector<std::string>\s+(?:cmd|command|argv|args|arguments|commandLine)\s*=\s*"
                             r"\{\s*\"([^\"]+)\"", text):
            add_program(m.group(1), f"{rel}:{line_of(text, m.start())}", needs)
        # for (const char* candidate : {"python3", "/usr/bin/python3"}) SPAWN(candidate, ...): each one.
        for m in re.finditer(r"for\s*\([^;:)]*:\s*\{([^}]*)\}\s*\)([^;]*)", text):
            if re.search(r"\b(?:" + calls + r")\s*\(", m.group(2)):
                for s in CXX_STRING.finditer(m.group(1)):
                    add_program(s.group(1), f"{rel}:{line_of(text, m.start())}", needs)


def add_program(word, where, needs):
    name = program_name(word)
    if name and not name.startswith("-") and re.match(r"^[A-Za-z0-9_.+-]+$", name):
        needs.add("program", name, where)


# ---- Resolution ----------------------------------------------------------------------------------

def local_python_modules(repo, files):
    names = set()
    for rel in files:
        if rel.endswith(".py"):
            names.add(os.path.basename(rel)[:-3])
            if os.path.basename(rel) == "__init__.py":
                names.add(os.path.basename(os.path.dirname(rel)))
    return names


def resolve(kind, name, context):
    """("packages", [(package, evidence)]) | ("base", package) | ("ok", why) | ("unknown", advice)."""
    # The kinds that are one table lookup: (table, its name for the advice).
    tables = {"cmake": (CMAKE_PACKAGES, "CMAKE_PACKAGES"), "language": (CMAKE_LANGUAGES, "CMAKE_LANGUAGES"),
              "pkg-config": (PKG_CONFIG_MODULES, "PKG_CONFIG_MODULES"),
              "cmake-library": (CMAKE_LIBRARIES, "CMAKE_LIBRARIES")}
    if kind in tables:
        table, table_name = tables[kind]
        row = table.get(name)
        return ("packages", row) if row else ("unknown", table_name)
    if kind == "runtime":
        return ("packages", RUNTIME_STRINGS[name])
    if kind == "header":
        if name in STD_CXX_HEADERS:
            return ("ok", "the C++ standard library")
        if name.startswith(context["local_headers"]) or name in context["local_header_names"]:
            return ("ok", "this repository")
        for prefix in sorted(HEADERS, key=len, reverse=True):
            if name.startswith(prefix):
                return ("packages", HEADERS[prefix])
        return ("unknown", "HEADERS")
    if kind == "python":
        if f"python:{name}" in NOT_FROM_DEBIAN:
            return ("ok", NOT_FROM_DEBIAN[f"python:{name}"])
        if name in PYTHON_MODULES:
            return ("packages", PYTHON_MODULES[name])
        if name in sys.stdlib_module_names:
            return ("ok", "the Python standard library (python3)")
        if name in context["local_python"]:
            return ("ok", "this repository")
        return ("unknown", "PYTHON_MODULES")
    if kind == "program":
        if f"program:{name}" in NOT_FROM_DEBIAN:
            return ("ok", NOT_FROM_DEBIAN[f"program:{name}"])
        if name in PROGRAMS:
            return ("packages", PROGRAMS[name])
        if name in BASE_PROGRAM_PACKAGE:
            return ("base", BASE_PROGRAM_PACKAGE[name])
        if is_project_program(name, context["targets"]) or name in context["tree_names"]:
            return ("ok", "built by or kept in this repository")
        return ("unknown", "PROGRAMS")
    raise ValueError(kind)


def describe(kind, name):
    return {
        "cmake": lambda: f"find_package({name.replace('/', ' COMPONENTS ')})",
        "language": lambda: f"project(LANGUAGES {name})",
        "pkg-config": lambda: f"pkg_check_modules({name})",
        "cmake-library": lambda: f"find_library/find_path({name})",
        "runtime": lambda: f"the runtime component {name}",
        "header": lambda: f"#include <{name}>",
        "python": lambda: f"python import {name}",
        "program": lambda: f"the program {name}",
    }[kind]()


HOW_TO_FIND = {
    "CMAKE_PACKAGES": "dpkg -S on the Config.cmake file or header CMake finds",
    "CMAKE_LANGUAGES": "dpkg -S $(which COMPILER)",
    "PKG_CONFIG_MODULES": "dpkg -S NAME.pc",
    "CMAKE_LIBRARIES": "dpkg -S on the library or header",
    "HEADERS": "dpkg -S /usr/include/HEADER",
    "PYTHON_MODULES": "dpkg -S /usr/lib/python3/dist-packages/MODULE, or NOT_FROM_DEBIAN for one from PyPI",
    "PROGRAMS": "dpkg -S $(which PROGRAM)",
}


def check(repo, list_path=None):
    """The problems found (one line each), and the resolved needs."""
    list_path = list_path or os.path.join(repo, PACKAGE_LIST)
    problems = []
    if not os.path.isfile(list_path):
        return [f"{PACKAGE_LIST}: missing"], {}
    entries = read_package_list(list_path)
    listed = {p: n for p, n, _ in entries}
    for p, n, comment in entries:
        if not comment:
            problems.append(f"{PACKAGE_LIST}:{n}: {p}: say what uses it (`{p}  # what uses it`, one package a line)")
    setup = os.path.join(repo, "scripts/setup.sh")
    if os.path.isfile(setup):
        text = read(repo, "scripts/setup.sh")
        if "debian-packages.txt" not in text or re.search(r"^\s*packages=\(", text, re.MULTILINE):
            problems.append("scripts/setup.sh: must install the packages of scripts/debian-packages.txt "
                            "(read from the file, no list of its own)")

    files = tree_files(repo)
    kinds = classify(repo, files)
    needs = Needs()
    targets = cmake_targets(repo, kinds["cmake"])
    scan_cmake(repo, kinds["cmake"], needs, targets)
    scan_cxx(repo, kinds["cxx"], needs)
    scan_python(repo, kinds["python"], needs)
    scan_shell(repo, kinds["shell"], needs)
    include_roots = tuple(sorted({rel.split("/")[0] + "/" for rel in files} |
                                 {"/".join(rel.split("/")[1:2]) + "/" for rel in files
                                  if rel.startswith(("src/", "shaders/", "tests/")) and rel.count("/") > 1}))
    context = {
        "targets": targets,
        "local_python": local_python_modules(repo, files),
        "local_headers": include_roots,
        "local_header_names": {os.path.basename(rel) for rel in files},
        "tree_names": {os.path.basename(rel) for rel in files if os.access(os.path.join(repo, rel), os.X_OK)},
    }
    used = set()
    resolved = {}
    for (kind, name), where in sorted(needs.items.items(), key=lambda kv: kv[1]):
        how, detail = resolve(kind, name, context)
        resolved[(kind, name)] = (where, how, detail)
        if how == "unknown":
            problems.append(
                f"{where}: {describe(kind, name)}: no Debian package known for it. Add the package that "
                f"provides it to {PACKAGE_LIST} (with what uses it) and a row to {detail} in {THIS_FILE} "
                f"({HOW_TO_FIND[detail]})")
        elif how == "packages":
            for package, _ in detail:
                used.add(package)
                if package not in listed:
                    problems.append(f"{where}: {describe(kind, name)} needs the Debian package {package}, which "
                                    f"{PACKAGE_LIST} does not list: add `{package}  # what uses it` there "
                                    f"(scripts/setup.sh installs the list)")
    for p, n, _ in entries:
        if p not in used and p not in INFRASTRUCTURE:
            problems.append(f"{PACKAGE_LIST}:{n}: {p}: nothing found in the tree needs it (no find_package, "
                            f"#include, import or program of the tables maps to it): remove it, or add what "
                            f"needs it to the tables or to INFRASTRUCTURE in {THIS_FILE}")
    return problems, resolved


# ---- Self-test: a fake tree with one omission of every kind --------------------------------------

FAKE_LIST = """\
build-essential  # the compiler
libglm-dev       # find_package(glm)
python3          # the interpreter
xvfb             # xvfb-run
mesa-vulkan-drivers  # lavapipe
cowsay           # listed, used by nothing
libgtest-dev
"""
FAKE_TREE = {
    "CMakeLists.txt": """\
cmake_minimum_required(VERSION 3.25)
project(fake LANGUAGES CXX)
find_package(glm REQUIRED)
find_package(Boost REQUIRED COMPONENTS filesystem) # unknown
find_package(JPEG REQUIRED) # known, package not listed
find_package(Python3 REQUIRED COMPONENTS Interpreter)
find_program(MAGICK magick)
add_executable(fake src/main.cpp)
add_test(NAME t COMMAND frob-cmake-tool --check)
""",
    "src/main.cpp": """\
#include <vector>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <boost/asio.hpp>
#include "fake.h"
int main() {
    std::system("convert in.png out.jpg");
    runProcess({"xvfb-run", "-a", "true"}, {});
    runPython("python3", {"-c", "import scipy"}, true);
    const char* layer = "VK_LAYER_KHRONOS_validation";
}
""",
    "src/fake.h": "#pragma once\n",
    "tools/plot.py": "import os\nimport yaml\nfrom numpy import linalg\nimport fakelocal\n"
                     "import subprocess\nsubprocess.run(['rsync', '-a', 'x', 'y'])\n",
    "tools/fakelocal.py": "import json\n",
    "scripts/run.sh": """\
#!/usr/bin/env bash
set -euo pipefail
here=$(dirname "$0")
helper() { frobnicate --all; }
helper
out=$(mktemp -d) && jq . "$out/x.json" | sort > /dev/null
python3 -c "import requests, sys; sys.exit(0)"
python3 - "$out" <<'PY'
import sys, pandas
PY
if ! command -v shellcheck >/dev/null; then echo "no shellcheck"; fi
$SUDO apt-get install -y foo
"$here/../build/fake" --version
""",
}
# (a substring each report must contain, the problem it stands for)
FAKE_EXPECTED = [
    ("find_package(Boost): no Debian package known", "an unknown find_package"),
    ("find_package(Boost COMPONENTS filesystem): no Debian package known", "an unknown component"),
    ("find_package(JPEG) needs the Debian package libjpeg-dev", "a known find_package whose package is not listed"),
    ("the program magick: no Debian package known", "an unknown find_program"),
    ("the program frob-cmake-tool: no Debian package known", "an unknown program in a CMake COMMAND"),
    ("#include <boost/asio.hpp>: no Debian package known", "an unknown header"),
    ("the program convert: no Debian package known", "a program run through std::system"),
    ("the program xvfb-run needs the Debian package xauth", "a program whose second package is not listed"),
    ("python import scipy: no Debian package known", "an import in a C++ string"),
    ("the runtime component VK_LAYER_KHRONOS_validation needs the Debian package vulkan-validationlayers",
     "a runtime component whose package is not listed"),
    ("python import yaml: no Debian package known", "an unknown import"),
    ("python import numpy needs the Debian package python3-numpy", "a known import whose package is not listed"),
    ("the program rsync: no Debian package known", "a program run through subprocess"),
    ("the program frobnicate: no Debian package known", "a program in a shell function"),
    ("the program jq: no Debian package known", "a program in a pipeline after a substitution"),
    ("python import requests: no Debian package known", "an import in python3 -c"),
    ("python import pandas: no Debian package known", "an import in a python heredoc"),
    ("the program shellcheck: no Debian package known", "a program looked up with command -v"),
    ("cowsay: nothing found in the tree needs it", "a listed package nothing uses"),
    ("libgtest-dev: say what uses it", "a listed package without its comment"),
]
# Must not be reported: resolved through the list, the base system, the tree or NOT_FROM_DEBIAN.
FAKE_NOT_REPORTED = ["find_package(glm)", "find_package(Python3)", "find_package(Python3 COMPONENTS Interpreter)",
                     "project(LANGUAGES CXX)", "#include <vector>", "#include <glm/glm.hpp>", "python import os",
                     "python import fakelocal", "python import json", "python import sys",
                     "python import subprocess", "the program mktemp", "the program sort", "the program apt-get",
                     "the program sudo", "the program helper", "the program fake", "the program xvfb-run needs "
                     "the Debian package xvfb", "the program python3", "the program dirname"]


def self_test():
    failures = []
    with tempfile.TemporaryDirectory(prefix="pt_setup_guard_") as root:
        for rel, text in FAKE_TREE.items():
            os.makedirs(os.path.dirname(os.path.join(root, rel)) or root, exist_ok=True)
            with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                f.write(text)
        os.makedirs(os.path.join(root, "scripts"), exist_ok=True)
        with open(os.path.join(root, PACKAGE_LIST), "w", encoding="utf-8") as f:
            f.write(FAKE_LIST)
        problems, _ = check(root)
        report = "\n".join(problems)
        for needle, what in FAKE_EXPECTED:
            if needle not in report:
                failures.append(f"not reported: {what} ({needle!r})")
        for subject in FAKE_NOT_REPORTED:
            for p in problems:
                if f": {subject}:" in p or f": {subject} needs" in p or p.endswith(f": {subject}"):
                    failures.append(f"reported though it resolves: {subject}: {p}")
        if len(problems) != len(FAKE_EXPECTED):
            failures.append(f"{len(problems)} problems reported, {len(FAKE_EXPECTED)} expected")
        # A fake tree that needs only listed packages passes: the guard does not cry wolf.
        clean_root = os.path.join(root, "clean")
        os.makedirs(os.path.join(clean_root, "scripts"))
        with open(os.path.join(clean_root, "CMakeLists.txt"), "w") as f:
            f.write("project(clean LANGUAGES CXX)\nfind_package(glm REQUIRED)\n")
        with open(os.path.join(clean_root, "scripts", "x.sh"), "w") as f:
            f.write("#!/bin/sh\nxvfb-run -a true | grep x\n")
        with open(os.path.join(clean_root, PACKAGE_LIST), "w") as f:
            f.write("build-essential  # c++\nlibglm-dev  # glm\nxvfb  # xvfb-run\nxauth  # xvfb-run\n")
        clean_problems, _ = check(clean_root)
        failures += [f"clean tree reported: {p}" for p in clean_problems]
    if failures:
        print("\n".join(["self-test: the guard misses omissions:"] + failures + ["", "its report was:", report]))
        return 1
    print(f"self-test: all {len(FAKE_EXPECTED)} planted omissions reported, nothing else; "
          f"a clean tree passes. One report, for example:\n  "
          f"{next(p for p in problems if 'find_package(Boost)' in p)}")
    return 0


# ---- Machine verification: the tables against dpkg ------------------------------------------------

def dpkg_owner(paths):
    """{path: package} for the paths dpkg knows (usrmerge: /bin/x for /usr/bin/x as well)."""
    query = []
    for p in paths:
        query.append(p)
        if p.startswith("/usr/bin/"):
            query.append("/bin/" + p[len("/usr/bin/"):])
    out = subprocess.run(["dpkg", "-S", *query], capture_output=True, text=True)
    owners = {}
    for line in out.stdout.splitlines():
        pkgs, _, path = line.partition(": ")
        owners[path.strip()] = [q.split(":")[0].strip() for q in pkgs.split(",")]
    result = {}
    for p in paths:
        alt = "/bin/" + p[len("/usr/bin/"):] if p.startswith("/usr/bin/") else None
        result[p] = owners.get(p) or (owners.get(alt) if alt else None)
    return result


def installed_fields(packages):
    out = subprocess.run(["dpkg-query", "-W", "-f=${Package}\t${Status}\t${Essential}\t${Priority}\t${Depends}"
                          "\t${Pre-Depends}\n", *packages], capture_output=True, text=True)
    fields = {}
    for line in out.stdout.splitlines():
        name, status, essential, priority, depends, pre = (line.split("\t") + [""] * 6)[:6]
        if "install ok installed" in status:
            deps = []
            for part in (depends + "," + pre).split(","):
                deps += [re.sub(r"[ (:].*", "", alt.strip()) for alt in part.split("|") if alt.strip()]
            fields[name.split(":")[0]] = (essential, priority, deps)
    return fields


def closure(package, depth=4):
    """The package and what it depends on, installed, to `depth` levels."""
    seen, frontier = {package}, [package]
    for _ in range(depth):
        fields = installed_fields(frontier)
        frontier = [d for f in fields.values() for d in f[2] if d not in seen]
        seen.update(frontier)
        if not frontier:
            break
    return seen


def verify_machine(repo):
    if not shutil.which("dpkg") or not shutil.which("apt-cache"):
        print("verify: no dpkg/apt-cache here (not Debian): skipped")
        return 77
    problems = []
    listed = [p for p, _, _ in read_package_list(os.path.join(repo, PACKAGE_LIST))]
    out = subprocess.run(["apt-cache", "show", "--no-all-versions", *listed], capture_output=True, text=True)
    # A package exists when apt knows it, or when it is installed (apt's lists may have been cleaned).
    known = set(re.findall(r"^Package: (\S+)", out.stdout, re.MULTILINE)) | set(installed_fields(listed))
    for p in listed:
        if p not in known:
            problems.append(f"{PACKAGE_LIST}: {p}: no such package (apt-cache show knows none, none installed)")
    rows = []
    for table_name, table in (("CMAKE_PACKAGES", CMAKE_PACKAGES), ("CMAKE_LANGUAGES", CMAKE_LANGUAGES),
                              ("HEADERS", HEADERS), ("PYTHON_MODULES", PYTHON_MODULES), ("PROGRAMS", PROGRAMS),
                              ("RUNTIME_STRINGS", RUNTIME_STRINGS)):
        for key, row in table.items():
            for package, evidence in row:
                rows.append((f"{table_name}[{key!r}]", package, evidence))
    for package, (why, evidence) in INFRASTRUCTURE.items():
        rows.append((f"INFRASTRUCTURE[{package!r}]", package, evidence))
    installed = installed_fields(listed)
    files = {}
    for where, package, evidence in rows:
        if package not in listed:
            continue  # a table row for a package the tree does not use: nothing to verify here
        matches = sorted(glob.glob(evidence))
        if not matches:
            if package in installed:
                problems.append(f"{where}: {evidence}: no such file, though {package} is installed: fix the row")
            else:
                problems.append(f"{where}: {package} is not installed here (run scripts/setup.sh)")
            continue
        files[matches[-1]] = (where, package)
    owners = dpkg_owner(list(files))
    closures = {}
    for path, (where, package) in files.items():
        owner = owners.get(path)
        if not owner:
            problems.append(f"{where}: dpkg -S {path}: no package owns it")
            continue
        if package not in closures:
            closures[package] = closure(package)
        if not set(owner) & closures[package]:
            problems.append(f"{where}: {path} belongs to {', '.join(owner)}, which {package} does not bring "
                            f"(dpkg -S; checked to 4 levels of Depends)")
    base = sorted(set(BASE_PROGRAM_PACKAGE.values()))
    fields = installed_fields(base)
    for pkg in base:
        if pkg not in fields:
            problems.append(f"BASE_PROGRAMS[{pkg!r}]: not installed here, so not part of the base system")
        elif fields[pkg][0] != "yes" and fields[pkg][1] != "required":
            problems.append(f"BASE_PROGRAMS[{pkg!r}]: neither Essential nor Priority: required "
                            f"({fields[pkg][0]}, {fields[pkg][1]}): move its programs to PROGRAMS and the list")
    programs = [f"/usr/bin/{p}" for p in BASE_PROGRAM_PACKAGE if p not in SHELL_BUILTINS or p in ("echo",)]
    owners = dpkg_owner(programs)
    for path in programs:
        want = BASE_PROGRAM_PACKAGE[os.path.basename(path)]
        if owners.get(path) and want not in owners[path]:
            problems.append(f"BASE_PROGRAMS: {path} belongs to {', '.join(owners[path])}, not {want}")
    if problems:
        print("\n".join(["verify: the tables disagree with this machine:"] + problems))
        return 1
    print(f"verify: {len(files)} table rows agree with dpkg -S; {len(listed)} listed packages exist; "
          f"{len(base)} base packages are Essential or required")
    return 0


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    flags = {a for a in sys.argv[1:] if a.startswith("--")}
    repo = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), "..", ".."))
    if sys.version_info < (3, 10):
        print("setup test: needs Python 3.10 or later (sys.stdlib_module_names)")
        return 1
    if "--self-test" in flags:
        return self_test()
    if "--verify-machine" in flags:
        return verify_machine(repo)
    problems, resolved = check(repo)
    if "--list" in flags:
        for (kind, name), (where, how, detail) in sorted(resolved.items()):
            what = ", ".join(p for p, _ in detail) if how == "packages" else (
                f"base system ({detail})" if how == "base" else detail)
            print(f"{describe(kind, name):60} {what:40} {where}")
    if problems:
        print("\n".join([f"setup: {len(problems)} problem(s) with {PACKAGE_LIST}:"] + problems))
        return 1
    packages = {p for _, how, d in resolved.values() if how == "packages" for p, _ in d}
    print(f"setup: {len(resolved)} dependencies found (find_package, #include, import, program) resolve to "
          f"{len(packages)} listed packages, the standard library, the base system or this tree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
