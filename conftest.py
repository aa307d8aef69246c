"""pytest configuration shared by the unit tests and nbval."""


def pytest_collectstart(collector):
    # ipywidgets views carry a fresh random model id on every run: never compare them
    if getattr(collector, "fspath", None) is not None and collector.fspath.ext == ".ipynb":
        collector.skip_compare += ("application/vnd.jupyter.widget-view+json",)


def _start_kernel_twice(start):
    """nbval's kernel start, tried a second time when the kernel dies before its first reply. With two pytest
    workers each starting kernels, a fresh kernel can lose the race for the ports jupyter_client picked for it
    and exit at once (seen once in CI as "Kernel died before replying to kernel_info": every cell of that
    notebook errored). Only the start is retried — a cell's verdict never is."""
    import functools
    import warnings

    @functools.wraps(start)
    def wrapped(*args, **kwargs):
        try:
            return start(*args, **kwargs)
        except RuntimeError as exc:
            if "Kernel died before replying" not in str(exc):
                raise
            warnings.warn(f"a notebook kernel died while starting ({exc}); starting another", stacklevel=2)
            return start(*args, **kwargs)

    return wrapped


def pytest_configure(config):
    try:
        from nbval import kernel
    except ImportError:  # (the web and LMS environments have no nbval)
        return
    if not getattr(kernel.start_new_kernel, "__wrapped__", None):
        kernel.start_new_kernel = _start_kernel_twice(kernel.start_new_kernel)
