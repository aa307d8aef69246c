"""The stored notebooks in JupyterLab, untrusted — as a student opens a copy handed out by an LMS, in plain
JupyterLab: a fresh Jupyter data folder holds no notebook signature, so no notebook is trusted. The stored
animations (animated PNGs) play; no output needs trust. JupyterLab is the lab environment's (.venv, make install),
with the project's settings (etc/jupyterlab-overrides.json, as make lab and the live site use them)."""

import os
import shutil
import socket
import subprocess
import time
import urllib.request

import pytest

from .conftest import ANIMATED, ROOT, plays, watch

LAB = ROOT / ".venv" / "bin" / "jupyter-lab"


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def lab(tmp_path_factory):
    if not LAB.exists():
        pytest.fail(f"{LAB} is missing: run `make install` (make test-web does)")
    tmp = tmp_path_factory.mktemp("lab")
    notebooks = tmp / "notebooks"
    notebooks.mkdir()
    for chapter in ANIMATED:
        shutil.copy2(ROOT / "chapters" / f"{chapter}.ipynb", notebooks)
    settings = tmp / "app-settings"
    settings.mkdir()
    shutil.copy2(ROOT / "etc" / "jupyterlab-overrides.json", settings / "overrides.json")
    env = dict(os.environ, JUPYTER_DATA_DIR=str(tmp / "data"), JUPYTER_CONFIG_DIR=str(tmp / "config"),
               JUPYTER_RUNTIME_DIR=str(tmp / "runtime"), IPYTHONDIR=str(tmp / "ipython"))
    port = _free_port()
    cmd = [str(LAB), "--no-browser", f"--port={port}", "--ServerApp.ip=127.0.0.1", "--IdentityProvider.token=",
           "--ServerApp.password=", f"--ServerApp.root_dir={notebooks}", f"--LabApp.app_settings_dir={settings}"]
    if os.geteuid() == 0:
        cmd.append("--allow-root")
    log = open(tmp / "lab.log", "w")
    proc = subprocess.Popen(cmd, env=env, stdout=log, stderr=subprocess.STDOUT)
    url = f"http://127.0.0.1:{port}"
    try:
        for _ in range(240):
            try:
                urllib.request.urlopen(f"{url}/api/status", timeout=2)
                break
            except OSError:
                if proc.poll() is not None:
                    pytest.fail(f"jupyter lab exited: {(tmp / 'lab.log').read_text()[-2000:]}")
                time.sleep(0.5)
        assert not list((tmp / "data").glob("nbsignatures*")), "a signature database: notebooks could be trusted"
        yield url
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()
        log.close()


def test_stored_animations_play_untrusted(browser, lab, offline, screenshots):
    for chapter in ANIMATED:
        page = watch(browser.new_page(viewport={"width": 1280, "height": 1000}), offline)
        page.set_default_timeout(120_000)
        page.goto(f"{lab}/lab/tree/{chapter}.ipynb?reset")  # (reset: no tab of another notebook restored)
        cells = page.locator(".jp-NotebookPanel:visible .jp-CodeCell", has_text="animation_png(")
        cells.first.wait_for()
        for k in range(cells.count()):
            out = cells.nth(k).locator(".jp-OutputArea-output")
            img = out.locator("img")
            assert img.count() == 1 and plays(page, img), f"animation {k + 1} of {chapter} does not play"
        # no toast asking about "official Jupyter news" over the notebook (and no request to the news feed)
        assert page.locator(".Toastify__toast", has_text="Jupyter news").count() == 0
        page.screenshot(path=str(screenshots / f"lab-untrusted-{chapter}-animation.png"))
        page.close()
