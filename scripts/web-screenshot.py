"""A screenshot of the live page (scripts/web.sh's site) in headless Chromium
with WebGPU on SwiftShader, after its first frame is drawn.

    python3 scripts/web-screenshot.py SITE OUT.png

Serves SITE on 127.0.0.1; the page (`?screenshot`) holds a request to /hold
open until its frame is drawn, which keeps Chromium's virtual time, and so
its screenshot, waiting."""
import http.server, subprocess, sys, tempfile, threading

site, out = sys.argv[1], sys.argv[2]
drawn = threading.Event()


class Handler(http.server.SimpleHTTPRequestHandler):
    def __init__(self, *a, **k):
        super().__init__(*a, directory=site, **k)

    def log_message(self, *a):
        pass

    def do_GET(self):
        if self.path == "/hold":
            drawn.wait(600)
        if self.path == "/release":
            drawn.set()
        if self.path in ("/hold", "/release"):
            self.send_response(204)
            self.end_headers()
            return
        super().do_GET()


Handler.extensions_map[".wasm"] = "application/wasm"
server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
threading.Thread(target=server.serve_forever, daemon=True).start()
with tempfile.TemporaryDirectory() as profile:
    subprocess.run(
        ["chromium", "--headless=new", "--no-sandbox", "--enable-unsafe-webgpu",
         "--use-webgpu-adapter=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--no-first-run",
         f"--user-data-dir={profile}", "--window-size=1100,560",
         "--virtual-time-budget=600000", f"--screenshot={out}",
         f"http://127.0.0.1:{server.server_address[1]}/?screenshot"],
        check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, timeout=900)
print("drawn" if drawn.is_set() else "NOT drawn: the screenshot shows the page before its frame")
