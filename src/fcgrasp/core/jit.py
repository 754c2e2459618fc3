"""numba for the package's compiled loops: whether to compile (``FCGRASP_JIT``,
:func:`jit_setting`), numba's import for them (:func:`import_numba`, after which
:func:`started` is True), plain-Python functions compiled over one namespace with their
machine code cached on disk and loaded without numba's registry refresh
(:func:`njit_all`), a module's loops compiled on first use (:class:`CompiledLoops`), and
the one warning of a loop that falls back to numpy (:func:`fell_back`).

The compiled loops themselves live beside the work they do (:mod:`fcgrasp.core.kernels`,
the stretch search's, the jaw's ...); this module is what they share."""

from __future__ import annotations

import os
import sys
import threading
import types
import warnings
from typing import Any

__all__ = ["jit_setting", "started", "import_numba", "njit_all", "CompiledLoops",
           "KernelFallbackWarning", "fell_back"]

#: numba imported by this package's compiled loops in this process (:func:`started`)
_numba_started = False


def jit_setting() -> bool | None:
    """``FCGRASP_JIT`` as set in the environment: False ("0", "off", "no", "false"):
    never compile; True ("1", "on", "yes", "true"): always; None (unset or anything
    else): when the work repays it.  Read at every decision, by these kernels and by
    the stretch search's (:mod:`fcgrasp.model.stretches._kernels`)."""
    setting = os.environ.get("FCGRASP_JIT", "auto").strip().lower()
    if setting in ("0", "off", "no", "false"):
        return False
    if setting in ("1", "on", "yes", "true"):
        return True
    return None


def started() -> bool:
    """Whether numba started in this process for the package's compiled loops (these
    kernels or any :class:`CompiledLoops`): its start-up (about 0.5 s of CPU, to import
    it and its target) is then paid, and loading more loops from its cache costs
    milliseconds, so the searches that wait for their work to repay the start-up
    (:func:`use_jit`, the stretch search's, the survivor rows') run compiled at once."""
    return _numba_started


_importing = threading.Lock()


def import_numba() -> Any:
    """numba, imported for the package's loops; None without it.

    numba's CPU target imports ``numba.np.arraymath`` on the first compile or cache load
    of a process, and that module asks at its import whether BLAS is there by importing
    ``scipy.linalg`` (about 0.15 s of numba's 0.5 s start-up: scipy's array-API layer; no
    loop of this package calls BLAS).  scipy is a dependency of this package, so the
    answer is known: ``arraymath`` is imported here with numba's ``ensure_blas``
    answering without the import, then ``ensure_blas`` is put back, so that numba's
    state is the one its own import gives (``_HAVE_BLAS`` True), and a jitted
    ``np.dot`` imports ``scipy.linalg`` when it is compiled.  Where scipy is missing, or
    numba's modules are not laid out so (another version), numba is imported as is.
    From then on numba has started for the package's loops (:func:`started`)."""
    global _numba_started
    try:
        import numba
    except ImportError:
        return None
    _numba_started = True
    with _importing:
        if "numba.np.arraymath" in sys.modules:
            return numba
        import importlib.util

        try:
            from numba.np import linalg
        except ImportError:             # pragma: no cover - another numba's layout
            return numba
        real = getattr(linalg, "ensure_blas", None)
        if real is None or importlib.util.find_spec("scipy") is None:
            return numba
        linalg.ensure_blas = _blas_there
        try:
            from numba.np import arraymath
        finally:
            linalg.ensure_blas = real
        if getattr(arraymath, "ensure_blas", None) is _blas_there:
            arraymath.ensure_blas = real
    return numba


def _blas_there() -> None:
    """numba's ``ensure_blas`` while :func:`import_numba` imports ``arraymath``: BLAS is
    there (scipy is)."""


def njit_all(numba: Any, namespace: dict[str, Any], funcs: list[tuple[str, Any]],
             borrowing: frozenset[str] = frozenset()) -> dict[str, Any]:
    """Compile plain-Python functions with numba, each rebuilt over ``namespace`` and
    stored there under its name, so that compiled functions call compiled ones (here
    and in :mod:`fcgrasp.model.stretches._kernels`).  The machine code is cached on disk
    beside the functions' module; where there is nowhere to write it (a read-only
    install), compiled without a cache.  Returns ``namespace``.

    The functions named in ``borrowing`` are compiled without numba's reference counts
    (its runtime off: ``_nrt=False``): they allocate nothing and only read and write the
    arrays they are given, which their caller holds for the call, and a small function
    called per pose or per edge otherwise pays an atomic increment and decrement per
    array argument per call (a third of the jaw's pose loop).  Where this numba does
    not take the option (an unknown option fails only at the first call, which would
    leave every loop to numpy), they are compiled as the others."""
    borrow = _takes_nrt_option()
    for name, func in funcs:
        clone = types.FunctionType(func.__code__, namespace, func.__name__, func.__defaults__)
        clone.__module__, clone.__qualname__ = func.__module__, func.__qualname__
        options: dict[str, Any] = {"error_model": "numpy"}
        if borrow and name in borrowing:
            options["_nrt"] = False
        try:
            namespace[name] = numba.njit(cache=True, **options)(clone)
        except RuntimeError:            # nowhere to cache (a read-only install): compile
            namespace[name] = numba.njit(**options)(clone)
        _light_loads(namespace[name])
    return namespace


def _takes_nrt_option() -> bool:
    """Whether this numba's CPU target takes ``_nrt`` (:func:`njit_all`'s
    ``borrowing``), read from its table of options."""
    try:
        from numba.core.cpu import CPUTargetOptions
    except ImportError:                 # pragma: no cover - another numba's layout
        return False
    return hasattr(CPUTargetOptions, "_nrt")


_LIGHT: dict[type, Any] = {}


def _light_loads(dispatcher: Any) -> None:
    """Load ``dispatcher``'s machine code from numba's cache without refreshing numba's
    registries.

    numba's cache refreshes the target context before every load (``Cache.
    load_overload``): the first load of a process imports and installs every
    implementation numba has (its numpy, typed containers, random, ...: about 0.25 s of
    a fresh process's CPU, more than loading all of a gripper's loops).  A loop loaded
    from the cache is machine code already; all it needs is numba's runtime (the
    reference counts and allocator its code calls), which is initialized here as the
    refresh would.  Only the package's own dispatchers load so (their cache's class
    swapped for a subclass); a compile, on a miss, refreshes as before (numba's
    compiler does), and where numba's cache is not laid out so (another version), or
    the runtime cannot start, the cache loads as it does."""
    cache = getattr(dispatcher, "_cache", None)
    base = type(cache)
    if base not in _LIGHT:
        _LIGHT[base] = _light_class(base)
    light = _LIGHT[base]
    if light is not None:
        cache.__class__ = light


def _light_class(base: type) -> Any:
    """The subclass of numba's cache class ``base`` whose loads skip the refresh
    (:func:`_light_loads`), None where ``base`` is not laid out so."""
    try:
        from numba.core.runtime import rtsys
    except ImportError:                 # pragma: no cover - another numba's layout
        return None
    if not all(hasattr(base, name) for name in
               ("load_overload", "_load_overload", "_guard_against_spurious_io_errors")):
        return None

    class _LightCache(base):            # type: ignore[misc]
        def load_overload(self, sig: Any, target_context: Any) -> Any:
            try:
                rtsys.initialize(target_context)
            except Exception:           # pragma: no cover - numba's own load then
                return super().load_overload(sig, target_context)
            with self._guard_against_spurious_io_errors():
                return self._load_overload(sig, target_context)
            return None                 # the guard swallowed an error: not loaded

    return _LightCache


class CompiledLoops:
    """The numba loops of one module (``funcs``, plain Python over the module's
    ``namespace``), compiled or loaded from numba's cache once per process, on first
    use (:func:`njit_all`; ``extra()`` adds names compiled elsewhere, None when they
    cannot be had).  Used by the compiled simplex, three fingers with friction, the
    parallel jaw and the two-finger stretch search."""

    def __init__(self, namespace: dict[str, Any], funcs: tuple[Any, ...],
                 extra: Any = None, borrowing: tuple[Any, ...] = ()) -> None:
        self._namespace, self._funcs, self._extra = namespace, funcs, extra
        #: the names compiled without reference counts (:func:`njit_all`)
        self._borrowing = frozenset(f.__name__ for f in borrowing)
        self._lock = threading.Lock()
        self._loaded: dict[str, Any] = {}
        #: numba missing, or a loop that failed to compile: numpy from then on
        self.broken = False

    def get(self) -> dict[str, Any] | None:
        """The compiled loops by name; None without numba (or ``extra``'s names) and
        with ``FCGRASP_JIT=0``, which never compiles (every caller then runs numpy)."""
        if jit_setting() is False:
            return None
        with self._lock:
            if not self._loaded and not self.broken:
                numba = import_numba()
                if numba is None:
                    self.broken = True
                    return None
                names = dict(self._namespace)
                if self._extra is not None:
                    more = self._extra()
                    if more is None:
                        return None
                    names.update(more)
                self._loaded.update(njit_all(numba, names,
                                             [(f.__name__, f) for f in self._funcs],
                                             self._borrowing))
            return self._loaded or None

    @classmethod
    def of_modules(cls, modules: tuple[types.ModuleType, ...],
                   borrowing: tuple[Any, ...] = ()) -> CompiledLoops:
        """The loops of ``modules``: every function each defines, compiled over one
        namespace of their globals, so that a loop of one calls the compiled loops of
        the others."""
        namespace: dict[str, Any] = {}
        for module in modules:
            namespace.update(vars(module))
        funcs = tuple(f for module in modules for f in vars(module).values()
                      if isinstance(f, types.FunctionType) and f.__module__ == module.__name__)
        return cls(namespace, funcs, borrowing=borrowing)

    @property
    def loaded(self) -> bool:
        """Whether this process has compiled (or loaded) the loops already."""
        return bool(self._loaded)

    def available(self) -> bool:
        """Do the loops run here?  Not with ``FCGRASP_JIT=0``, without numba, or once
        one failed to compile."""
        return not self.broken and self.get() is not None

    def run(self, name: str, *args: Any) -> tuple[bool, Any]:
        """Run the loop ``name``: ``(True, what it returns)``, or ``(False, None)`` when
        the loops cannot run or numba fails to compile it (then :attr:`broken`, so that a
        broken numba never breaks a plan)."""
        loops = self.get()
        if loops is None:
            return False, None
        try:
            return True, loops[name](*args)
        except Exception as exc:        # numba's typing or lowering errors
            fell_back(name, exc)
            self.broken = True
            return False, None


class KernelFallbackWarning(UserWarning):
    """A compiled loop failed (numba could not type or lower it) and its module runs
    by numpy from then on: the plans are the same, 5 to 30 times slower."""


#: The loops that fell back to numpy in this process (each warned of once).
_fallen: set[str] = set()


def fell_back(name: str, exc: BaseException) -> None:
    """Say once per loop that ``name`` fell back to numpy (:class:`KernelFallbackWarning`);
    with ``FCGRASP_REQUIRE_JIT=1`` (the suite's setting: a numba upgrade that breaks a
    loop must fail it, not slow every plan) raise instead."""
    if os.environ.get("FCGRASP_REQUIRE_JIT", "").strip() in ("1", "yes", "true", "on"):
        raise RuntimeError(f"the compiled loop {name} failed and FCGRASP_REQUIRE_JIT is set: "
                           f"{type(exc).__name__}: {str(exc).splitlines()[0][:200]}") from exc
    if name not in _fallen:
        _fallen.add(name)
        warnings.warn(f"fcgrasp's compiled loop {name} failed ({type(exc).__name__}); "
                      "running by numpy from now on (the same plans, slower)",
                      KernelFallbackWarning, stacklevel=3)
