"""Typing into the studio's CodeMirror editor as a person does, for the browser tests."""
import json

CARET_LINE = ("(() => { const v = window.studio.editor; const p = v.state.selection.main.head; const l = v.state.doc.lineAt(p);"
              " return [l.number, p - l.from, l.text]; })()")


def _caret_after(words):
    return ("(() => { const v = window.studio.editor; const p = v.state.selection.main.head; const l = v.state.doc.lineAt(p);"
            " return l.text.slice(0, p - l.from).endsWith(%s); })()" % json.dumps(words))


def new_line(b, words):
    """Enter, as a key (CodeMirror opens the line and indents it as the line above), then `words`
    typed on it. Returns (caret, moved): [line, column, text] of the caret's line once the caret is
    after `words` (None if it never is), and whether End had to put it there.

    Beside stress-ng, Chromium's commit of typed text (Input.insertText) now and then reaches
    CodeMirror as a DOM change without the caret's new place: the words are in the text and the
    caret stays where it was, before them, so no completion opens. A person sees the caret there
    and presses End; so does this."""
    for kind in ("keyDown", "keyUp"):
        b.send("Input.dispatchKeyEvent", {"type": kind, "key": "Enter", "code": "Enter", "windowsVirtualKeyCode": 13,
                                          **({"text": "\r"} if kind == "keyDown" else {})})
    b.send("Input.insertText", {"text": words})
    try:
        b.wait_for(_caret_after(words), "the caret after the typed words", 5)
        return b.evaluate(CARET_LINE), False
    except Exception:
        pass
    line = b.evaluate(CARET_LINE)
    if not line or not line[2].rstrip().endswith(words.rstrip()):
        return None, False
    for kind in ("rawKeyDown", "keyUp"):
        b.send("Input.dispatchKeyEvent", {"type": kind, "key": "End", "code": "End", "windowsVirtualKeyCode": 35})
    try:
        b.wait_for(_caret_after(words), "the caret after the typed words, after End", 10)
    except Exception:
        return None, True
    return b.evaluate(CARET_LINE), True
