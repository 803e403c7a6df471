"""Builds the optional compiled parts of the catalog: the strip filter and the arrangement
search.  Without a C compiler the install still succeeds: without the arrangement search the
catalog uses plantri's generator, without the strip filter that generator uses its numpy
filter (the same records either way), and ``polyloops catalog`` says so when it runs."""

import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext


class OptionalBuildExt(build_ext):
    def run(self) -> None:
        try:
            super().run()
        except Exception as exc:  # no compiler, no Python headers
            self._skip("neither compiled part (strip filter, arrangement search) was built", exc,
                       "the catalog will use plantri's generator with the numpy filter")

    def build_extension(self, ext: Extension) -> None:
        try:
            super().build_extension(ext)
        except Exception as exc:
            if "_strips" in ext.name:
                self._skip("the compiled strip filter was not built", exc,
                           "plantri's generator will use the numpy filter")
            else:
                self._skip("the compiled arrangement search was not built", exc,
                           "the catalog will use plantri's generator")

    @staticmethod
    def _skip(what: str, exc: Exception, instead: str) -> None:
        print(f"polyloops: {what} ({exc}); {instead} (the same records, slower); "
              "'polyloops catalog' says so when it runs", file=sys.stderr)


setup(
    ext_modules=[Extension(f"polyloops.enumerate.{name}", [f"src/polyloops/enumerate/{name}.c"],
                           extra_compile_args=["-O2"], optional=True)
                 for name in ("_strips", "_arrangements")],
    cmdclass={"build_ext": OptionalBuildExt},
)
