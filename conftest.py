"""pytest configuration shared by the unit tests and nbval."""


def pytest_collectstart(collector):
    # ipywidgets views carry a fresh random model id on every run: never compare them
    if getattr(collector, "fspath", None) is not None and collector.fspath.ext == ".ipynb":
        collector.skip_compare += ("application/vnd.jupyter.widget-view+json",)
