# kinbook: two commands for a fresh machine that has python3 and make.
#   make lab   - create .venv, install kinbook with its extras, register the 'kinbook' kernel, open JupyterLab
#   make test  - create .venv if missing, install, run the unit tests, doctests and nbval on every notebook
#   make test-lms - nbgrader and otter-grader grade docs/lms.md's notebooks, in their own venv (.lms-venv)

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.kinbook-installed
PIN    := requirements/constraints.txt

.PHONY: lab lint test test-lms install kernel lock check-lock dist wheel-smoke clean notebooks test-cpu html web-env book lite \
	test-web lock-web chromium translations

install: $(STAMP)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(STAMP): pyproject.toml setup.py $(PIN) | $(BIN)/python
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -c $(PIN) -e '.[lab,test]'
	$(BIN)/python -m ipykernel install --sys-prefix --name kinbook --display-name "Python (kinbook)" >/dev/null
	touch $@

kernel: $(STAMP)

# root (a container, a CI box) needs --allow-root; everyone else gets the plain command
# No notebook needs trust: the stored animations are animated PNGs, which every front end shows untrusted.
# etc/jupyterlab-overrides.json: JupyterLab's windowed notebook (its default) lays out only the cells near the
# viewport; the whole notebook is laid out instead (the live site shares the setting).
lab: $(STAMP)
	mkdir -p chapters $(VENV)/share/jupyter/lab/settings
	cp etc/jupyterlab-overrides.json $(VENV)/share/jupyter/lab/settings/overrides.json
	$(BIN)/jupyter lab --notebook-dir=chapters $(if $(filter 0,$(shell id -u)),--allow-root)

# -n auto: one pytest worker per core (pytest-xdist); --dist loadfile keeps each notebook's cells in order on
# one worker (they share its kernel). JOBS=1 runs everything in this one process. -rs lists skipped tests with
# their reason (the grading sandbox's tests are skipped where bubblewrap cannot run).
# A notebook cell (or a notebook's kernel start) taking longer than CELL_TIMEOUT seconds fails as a hang: far beyond
# what any takes on a loaded machine (seconds on a quiet one; nbval's default of 60 s for a kernel start failed
# 13-4 once at load 15), so that a slow machine is never a failed test.
JOBS ?= auto
CELL_TIMEOUT ?= 600
test: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/python -m pytest --nbval --nbval-current-env --nbval-cell-timeout=$(CELL_TIMEOUT) --nbval-kernel-startup-timeout=$(CELL_TIMEOUT) -rs \
		$(if $(filter 1,$(JOBS)),,-n $(JOBS) --dist loadfile)

# Static analysis alone (make test runs it first): pyflakes, import order and bugbear, configured in pyproject.toml.
lint: $(STAMP)
	$(BIN)/ruff check .

# After changing a message: Babel extracts the marked messages (kinbook/i18n.py: N_, Np_, pN_; the mappings are
# pyproject.toml's [tool.babel]), merges them into each catalogue (a new message appears untranslated: translate it
# in kinbook/locale/<lang>/LC_MESSAGES/kinbook.po and run this again) and compiles the .mo files that are shipped.
translations: $(STAMP)
	mkdir -p build
	$(BIN)/pybabel -q extract -F pyproject.toml -k N_ -k Np_:1,2 -k pN_:1c,2 --no-location -w 120 \
		--project kinbook --copyright-holder "kinbook developers" -o build/kinbook.pot .
	$(BIN)/pybabel -q update -i build/kinbook.pot -d kinbook/locale -D kinbook --no-fuzzy-matching --ignore-obsolete -w 120
	$(BIN)/pybabel compile -d kinbook/locale -D kinbook --statistics

# The notebook tests again under another BLAS/SIMD profile: OpenBLAS's SSE3 (Prescott) kernels and numpy without
# its AVX2 (X86_V3) and AVX-512 (X86_V4, AVX512_*) loops. Outputs stored on one CPU and compared on another round
# differently; a notebook that prints round-off fails here even on the machine that stored it.
CPU_PROFILE := OPENBLAS_CORETYPE=Prescott NPY_DISABLE_CPU_FEATURES="X86_V3 X86_V4 AVX512_ICL AVX512_SPR"
test-cpu: $(STAMP)
	$(CPU_PROFILE) $(BIN)/python -m pytest --nbval --nbval-current-env --nbval-cell-timeout=$(CELL_TIMEOUT) --nbval-kernel-startup-timeout=$(CELL_TIMEOUT) chapters exercises \
		$(if $(filter 1,$(JOBS)),,-n $(JOBS) --dist loadfile)

# nbgrader 0.9.6 and otter-grader 7 pin jupyter packages on their own schedule: they get their own venv, pinned
# in requirements/lms.txt (the whole closure, so --no-deps), with kinbook editable and its kernel registered.
# uv installs the 150 pinned wheels in seconds where pip takes minutes; compiling their bytecode once at install
# saves each nbgrader/otter/kernel process compiling its imports again (CI may set PYTHONDONTWRITEBYTECODE).
LMS       := .lms-venv
LMS_PIN   := requirements/lms.txt
LMS_STAMP := $(LMS)/.kinbook-installed
UV        := uv==0.13.9

$(LMS_STAMP): pyproject.toml $(LMS_PIN)
	rm -rf $(LMS) && $(PYTHON) -m venv $(LMS)
	$(LMS)/bin/python -m pip install --quiet --disable-pip-version-check $(UV)
	$(LMS)/bin/uv pip install --quiet --python $(LMS)/bin/python --no-deps --compile-bytecode -r $(LMS_PIN)
	$(LMS)/bin/uv pip install --quiet --python $(LMS)/bin/python --no-deps -e .
	$(LMS)/bin/python -m ipykernel install --sys-prefix --name kinbook --display-name "Python (kinbook)" >/dev/null
	touch $@

# the nbgrader and the otter tests run side by side (one pytest worker each)
test-lms: $(LMS_STAMP)
	$(LMS)/bin/python -m pytest -p no:cacheprovider -n 2 --dist loadfile --durations=5 tests/lms/test_nbgrader.py tests/lms/test_otter.py

# Re-execute stored notebooks in place after a library change (NB=path to do only some)
NB ?= chapters/*.ipynb exercises/*.ipynb
notebooks: $(STAMP)
	$(BIN)/jupyter nbconvert --to notebook --execute --inplace --ExecutePreprocessor.kernel_name=kinbook \
		--ExecutePreprocessor.record_timing=False --ExecutePreprocessor.timeout=300 \
		--NotebookExporter.preprocessors=nbconvert.preprocessors.CoalesceStreamsPreprocessor $(wildcard $(NB))

# The chapters as standalone HTML pages that work offline: MathJax comes from the jupyter-server-mathjax package
# (copied next to the pages) instead of a CDN; the animation players need no icon font. Open build/html/*.html.
MATHJAX_DIR = $(shell $(BIN)/python -c "import jupyter_server_mathjax, os; print(os.path.join(os.path.dirname(jupyter_server_mathjax.__file__), 'static'))" 2>/dev/null)
# That package ships only the STIX-Web fonts: MathJax, which asks for its TeX fonts by default, then fell back to
# the browser's serif (upright variables, no bold vectors); local/offline.js points it at STIX-Web.
# etc/nbconvert/kinbook-html is nbconvert's lab template without its require.js from a CDN (no output uses it).
html: $(STAMP)
	mkdir -p build/html && rm -rf build/html/mathjax && cp -r $(MATHJAX_DIR) build/html/mathjax
	mkdir -p build/html/mathjax/config/local
	printf '%s\n' 'MathJax.Hub.Config({"HTML-CSS": {availableFonts: [], preferredFont: null, webFont: "STIX-Web", imageFont: null}});' \
		'MathJax.Ajax.loadComplete("[MathJax]/config/local/offline.js");' > build/html/mathjax/config/local/offline.js
	$(BIN)/jupyter nbconvert --to html --output-dir build/html \
		--TemplateExporter.extra_template_basedirs=etc/nbconvert --template kinbook-html \
		--HTMLExporter.mathjax_url="mathjax/MathJax.js?config=TeX-AMS-MML_HTMLorMML-full,Safe,local/offline" chapters/*.ipynb

# --- The lock and the package (issue 23) ---------------------------------------------------------------------------
#   make lock        - re-pin requirements/constraints.txt after a dependency change, for every supported Python
#   make check-lock  - the pins resolve kinbook[lab,test] on Python 3.10, 3.11.2 (Debian 12) ... 3.14 (no network
#                      beyond the package index; no interpreter of those versions needed)
#   make dist        - the sdist and the wheel in dist/
#   make wheel-smoke - the wheel installed in a fresh venv (with the grading extra) runs an instructor's workflow
# Their tools (uv, build) live in .venv-tools, pinned in requirements/tools.txt.
TOOLS       := .venv-tools
TOOLS_STAMP := $(TOOLS)/.kinbook-installed

$(TOOLS_STAMP): requirements/tools.txt
	rm -rf $(TOOLS) && $(PYTHON) -m venv $(TOOLS)
	$(TOOLS)/bin/python -m pip install --quiet --disable-pip-version-check -r requirements/tools.txt
	touch $@

lock: $(TOOLS_STAMP)
	PATH="$(CURDIR)/$(TOOLS)/bin:$$PATH" $(TOOLS)/bin/python requirements/lock.py

check-lock: $(TOOLS_STAMP)
	PATH="$(CURDIR)/$(TOOLS)/bin:$$PATH" $(TOOLS)/bin/python requirements/lock.py --check

dist: $(TOOLS_STAMP)
	rm -rf dist && $(TOOLS)/bin/python -m build --outdir dist .

wheel-smoke: dist
	.ci/wheel-smoke dist/kinbook-*.whl

# --- The workbook as a static website (issue #16), built with its own tools in .venv-web --------------------
#   make book      - the book (Jupyter Book 1), stored outputs as they are    -> build/site/
#   make lite      - the same notebooks live in the browser (JupyterLite)    -> build/site/live/
#   make test-web  - both, checked offline in Debian's chromium (Playwright)
# Only web-env uses the network (pip, npm); book and lite build offline.
WEB_VENV  := .venv-web
WEB_BIN   := $(WEB_VENV)/bin
WEB_STAMP := $(WEB_VENV)/.kinbook-web-installed
WEB_PIN   := requirements/web.txt

web-env: $(WEB_STAMP)

$(WEB_STAMP): $(WEB_PIN) requirements/lite-kernel.txt web/package.json web/package-lock.json
	test -x $(WEB_BIN)/python || $(PYTHON) -m venv $(WEB_VENV)
	$(WEB_BIN)/python -m pip install --quiet --disable-pip-version-check -r $(WEB_PIN)
	rm -rf $(WEB_VENV)/npm && mkdir -p $(WEB_VENV)/npm && cp web/package.json web/package-lock.json $(WEB_VENV)/npm/
	cd $(WEB_VENV)/npm && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error
	rm -rf $(WEB_VENV)/wheels && $(WEB_BIN)/python -m pip download --quiet --disable-pip-version-check --no-deps \
		--require-hashes -r requirements/lite-kernel.txt -d $(WEB_VENV)/wheels
	touch $@

book: $(WEB_STAMP) $(STAMP)
	$(WEB_BIN)/python web/build.py book

# The live site serves Pyodide itself, compiled (web/pyodide_site.py: assembled once into .venv-web/pyodide/).
lite: $(WEB_STAMP)
	$(WEB_BIN)/python web/build.py lite

# Debian's chromium drives the browser tests (Playwright downloads no browser); as root, install it when missing.
chromium:
	@test -x /usr/bin/chromium || { test "$$(id -u)" = 0 || { echo "make test-web needs Debian's chromium: apt-get install chromium" >&2; exit 1; }; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; }

# tests/web/test_lab.py opens the stored notebooks, untrusted, in the lab environment's JupyterLab ($(STAMP)).
test-web: book lite chromium $(STAMP)
	KINBOOK_TEST_WEB=1 $(WEB_BIN)/python -m pytest tests/web --confcutdir=tests/web -p no:cacheprovider -v -s

# Re-pin the website's tools (as `make lock` does for the lab/test environment).
lock-web:
	rm -rf .lock-web-venv && $(PYTHON) -m venv .lock-web-venv
	.lock-web-venv/bin/python -m pip install --quiet -r requirements/web.in
	{ head -n 2 $(WEB_PIN); .lock-web-venv/bin/python -m pip freeze --all | grep -v '^pip=='; } > $(WEB_PIN).new
	mv $(WEB_PIN).new $(WEB_PIN) && rm -rf .lock-web-venv

clean:
	rm -rf $(VENV) $(LMS) $(WEB_VENV) $(TOOLS) build dist *.egg-info
