# One task runner for people and CI alike (.ci/run calls `make test`).
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: demo test lint format bench clean browser dist fixtures

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip
	$(BIN)/pip install --quiet -e '.[test]'
	touch $(STAMP)

## demo: install, then audit the bundled example icon set on the bundled theme
demo: $(STAMP)
	$(BIN)/alpha-audit check themes/github-primer.yaml examples/vibrant/iconset.yaml --alpha 1.1

## browser: Debian's Chromium, Firefox ESR and WebKitGTK driver for the WebGL2 tests
## (apt-get only for what is missing, and only as root; otherwise a note and the tests skip)
BROWSER_PACKAGES = \
  $(if $(shell command -v chromium || echo "$$ALPHA_AUDIT_CHROMIUM"),,chromium) \
  $(if $(shell command -v firefox-esr || command -v firefox || echo "$$ALPHA_AUDIT_FIREFOX"),,firefox-esr libegl1 libegl-mesa0 libgl1-mesa-dri) \
  $(if $(shell command -v WebKitWebDriver && command -v Xvfb),,webkit2gtk-driver xvfb libgl1-mesa-dri)
browser:
	@[ -z "$(strip $(BROWSER_PACKAGES))" ] \
	  || { [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1 && apt-get update -qq \
	       && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(sort $(BROWSER_PACKAGES)) >/dev/null; } \
	  || echo "note: missing $(sort $(BROWSER_PACKAGES)); the WebGL2 tests skip those engines: sudo apt-get install -y $(sort $(BROWSER_PACKAGES))"

## dist: build the sdist and the wheel into dist/ and check their metadata
dist: $(STAMP)
	rm -rf dist
	$(BIN)/python -m build --quiet --outdir dist . >/dev/null
	$(BIN)/twine check --strict dist/*

## fixtures: the real Storybook and static page tests/pages audit, built with npm from
## tests/pages/site and cached outside the repository (tools/page_fixtures.py; rebuilt only
## when those sources change)
fixtures: $(STAMP)
	@command -v npm >/dev/null 2>&1 && $(BIN)/python tools/page_fixtures.py >/dev/null \
	  || echo "note: npm (Node.js 20.19+) is needed to build the test Storybook; tests/pages skips without it"

## test: install, then lint (ruff and mypy), build and check the distributions, and run the whole
## test suite on one pytest-xdist worker per core (TEST_WORKERS=0: in one process, no xdist)
TEST_WORKERS ?= auto
test: lint browser dist fixtures
	ALPHA_AUDIT_DIST=$(CURDIR)/dist $(BIN)/pytest -n $(TEST_WORKERS) --dist loadfile

## lint: ruff's lint and format checks, mypy --strict on src/alpha_audit ([tool.mypy]), then
## the layers as import contracts ([tool.importlinter]: a wrong import fails here)
lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks tools
	$(BIN)/ruff format --check src tests benchmarks tools
	$(BIN)/mypy
	$(BIN)/lint-imports --no-logo

format: $(STAMP)
	$(BIN)/ruff format src tests benchmarks tools
	$(BIN)/ruff check --fix src tests benchmarks tools

bench: $(STAMP)
	$(BIN)/python benchmarks/run.py

clean:
	rm -rf $(VENV) build dist src/*.egg-info .pytest_cache .hypothesis .ruff_cache .mypy_cache \
	  .import_linter_cache
