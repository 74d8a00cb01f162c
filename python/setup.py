"""Builds rollerpy with its native module and the roller program: setuptools (Debian's
python3-setuptools; pip install --no-build-isolation) runs the checkout's CMake build of the
targets _roller and roller and puts both inside the package (docs/python.md, "Installing rollerpy").

The build folder is the checkout's build/ (scripts/build.sh's, so that after a build pip only
copies), or $ROLLER_BUILD_DIR. The module is built for the interpreter that runs pip; one other than
Debian's /usr/bin/python3 gets its own build folder, build/python-<version>.
"""
import glob
import os
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def same_file(a, b):
    return os.path.exists(a) and os.path.exists(b) and os.path.samefile(a, b)


def build_folder():
    """The CMake build folder and the extra configure arguments for this interpreter."""
    if os.environ.get("ROLLER_BUILD_DIR"):
        return os.path.abspath(os.environ["ROLLER_BUILD_DIR"]), []
    if same_file(os.path.realpath(sys.executable), "/usr/bin/python3"):
        return os.path.join(ROOT, "build"), []
    version = "%d.%d" % sys.version_info[:2]
    return os.path.join(ROOT, "build", "python-" + version), ["-DPython_EXECUTABLE=" + sys.executable]


class CMakeExtension(Extension):
    """An extension CMake builds: no sources of its own for setuptools."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        if not os.path.isfile(os.path.join(ROOT, "CMakeLists.txt")):
            raise SystemExit("rollerpy: %s holds no CMakeLists.txt: install from roller's checkout "
                             "(pip install --no-build-isolation ./python from its root)" % ROOT)
        build, configure_args = build_folder()
        if not any(os.path.isfile(os.path.join(build, f)) for f in ("build.ninja", "Makefile")):
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            subprocess.run(["cmake", "-S", ROOT, "-B", build, "-DCMAKE_BUILD_TYPE=Release", "-DROLLER_PYTHON=ON",
                            "-DROLLER_PYTHON_DIR=" + os.path.join(build, "python")] + generator + configure_args,
                           check=True)
        subprocess.run(["cmake", "--build", build, "--target", "_roller", "roller", "-j", str(os.cpu_count() or 1)],
                       check=True)
        module_dir = self.module_dir(build)
        modules = glob.glob(os.path.join(module_dir, "_roller*.so"))
        if len(modules) != 1:
            raise SystemExit("rollerpy: expected one _roller*.so in %s after the build, found %s"
                             % (module_dir, modules))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copy2(modules[0], target)
        # The program beside the module: the commands that start roller (study, runner) find it there.
        program = os.path.join(os.path.dirname(target), "bin", "roller")
        os.makedirs(os.path.dirname(program), exist_ok=True)
        shutil.copy2(os.path.join(build, "roller"), program)

    @staticmethod
    def module_dir(build):
        """Where the build put the module: its cache's ROLLER_PYTHON_DIR."""
        with open(os.path.join(build, "CMakeCache.txt")) as cache:
            for line in cache:
                if line.startswith("ROLLER_PYTHON_DIR:"):
                    return line.split("=", 1)[1].strip()
        raise SystemExit("rollerpy: %s was configured without the Python module (ROLLER_PYTHON=OFF)" % build)


# setuptools' own files (build/, rollerpy.egg-info) in the CMake build folder, not beside the sources.
PIP_FILES = os.path.join(build_folder()[0], "pip")
os.makedirs(PIP_FILES, exist_ok=True)
setup(ext_modules=[CMakeExtension("rollerpy._roller")], cmdclass={"build_ext": CMakeBuild},
      options={"build": {"build_base": PIP_FILES}, "egg_info": {"egg_base": PIP_FILES}})
