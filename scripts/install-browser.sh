#!/usr/bin/env bash
# Install headless Chromium and ChromeDriver (Debian packages) for the report's browser tests.
# Never fails: without root (or sudo) the browser tests are skipped and say so.
set -u
if command -v chromium >/dev/null 2>&1 && command -v chromedriver >/dev/null 2>&1; then
  exit 0
fi
if ! command -v apt-get >/dev/null 2>&1; then
  echo "install-browser: no apt-get here; install chromium and chromedriver to run the browser tests"
  exit 0
fi
if [ "$(id -u)" = 0 ]; then SUDO=""; elif sudo -n true 2>/dev/null; then SUDO="sudo -n"; else
  echo "install-browser: not root and no sudo; the browser tests will be skipped"
  exit 0
fi
echo "install-browser: installing Debian's chromium and chromium-driver..."
$SUDO apt-get update -qq >/dev/null 2>&1
if ! DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium chromium-driver >/dev/null 2>&1; then
  echo "install-browser: apt-get could not install chromium; the browser tests will be skipped"
fi
exit 0
