"""A screenshot of the live page (scripts/web.sh's site) in headless Chromium
with WebGPU on SwiftShader, after its first frame is drawn.

    python3 scripts/web-screenshot.py SITE OUT.png [PAGE]

PAGE: the page and query to open (default `index.html`), e.g. the book's
`live/index.html?pipeline=occupancy.toml&set=techniques.shading%3Dmarschner`
with SITE the built book; `screenshot` is added to its query.

Serves SITE on 127.0.0.1 and drives Chromium over the DevTools protocol on a
pipe (--remote-debugging-pipe: fd 3 in, fd 4 out, NUL-terminated JSON). The
page (`?screenshot`) asks for /release once its first frame is drawn; then
the screenshot is taken. Real time, not --screenshot's virtual time: under
virtual time the page's clock stood still while the frame rendered, so its
status line said "0 ms"."""
import base64, http.server, json, os, subprocess, sys, tempfile, threading

site, out = sys.argv[1], sys.argv[2]
drawn = threading.Event()


class Handler(http.server.SimpleHTTPRequestHandler):
    def __init__(self, *a, **k):
        super().__init__(*a, directory=site, **k)

    def log_message(self, *a):
        pass

    def do_GET(self):
        if self.path == "/release":
            drawn.set()
            self.send_response(204)
            self.end_headers()
            return
        super().do_GET()


class DevTools:
    """Chromium's DevTools protocol on the two pipes it was given."""

    def __init__(self, to_browser, from_browser):
        self.to, self.frm, self.next_id, self.buffer = to_browser, from_browser, 0, b""

    def call(self, method, session=None, **params):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params}
        if session:
            message["sessionId"] = session
        os.write(self.to, json.dumps(message).encode() + b"\0")
        while True:  # events come in between; skip them
            reply = self.read()
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    sys.exit(f"{method}: {reply['error']}")
                return reply["result"]

    def read(self):
        while b"\0" not in self.buffer:
            chunk = os.read(self.frm, 1 << 16)
            if not chunk:
                sys.exit("Chromium closed its DevTools pipe")
            self.buffer += chunk
        message, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(message)


Handler.extensions_map[".wasm"] = "application/wasm"
server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
threading.Thread(target=server.serve_forever, daemon=True).start()
page = sys.argv[3] if len(sys.argv) > 3 else "index.html"
page += ("&" if "?" in page else "?") + "screenshot"
url = f"http://127.0.0.1:{server.server_address[1]}/{page}"
cmd_read, cmd_write = os.pipe()
res_read, res_write = os.pipe()


with tempfile.TemporaryDirectory() as profile:
    # bash puts the pipes at fd 3 and 4, where Chromium looks for them.
    browser = subprocess.Popen(
        ["bash", "-c", f'exec "$@" 3<&{cmd_read} 4>&{res_write}', "chromium",
         "chromium", "--headless=new", "--no-sandbox", "--enable-unsafe-webgpu",
         "--use-webgpu-adapter=swiftshader", "--enable-unsafe-swiftshader",
         "--disable-background-networking", "--no-first-run",
         f"--user-data-dir={profile}", "--window-size=1400,1300",
         "--remote-debugging-pipe", url],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
        pass_fds=(cmd_read, res_write))
    os.close(cmd_read)
    os.close(res_write)
    devtools = DevTools(cmd_write, res_read)
    try:
        if not drawn.wait(900):
            sys.exit("NOT drawn: the page never asked for /release")
        pages = [t for t in devtools.call("Target.getTargets")["targetInfos"] if t["type"] == "page"]
        session = devtools.call("Target.attachToTarget", targetId=pages[0]["targetId"],
                                flatten=True)["sessionId"]
        # The window's size less the browser's own frame is the viewport:
        # set the page's size itself.
        devtools.call("Emulation.setDeviceMetricsOverride", session=session, width=1400,
                      height=1300, deviceScaleFactor=1, mobile=False)
        shot = devtools.call("Page.captureScreenshot", session=session, format="png")
        with open(out, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        devtools.call("Browser.close")
    finally:
        browser.kill()
        browser.wait()
print(f"drawn: {out}")
