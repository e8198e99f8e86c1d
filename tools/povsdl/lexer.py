"""POV-Ray's scene language as tokens (numbers, names, strings, directives, punctuation).

Comments are skipped: `//` to the end of the line and `/* */`, which nest in POV-Ray.
"""
import re


class PovError(Exception):
    """A construct the converter refuses, at a line and column of the file (both from 1)."""

    def __init__(self, line, col, message):
        super().__init__(message)
        self.line = line
        self.col = col
        self.message = message


class Token:
    __slots__ = ("kind", "text", "line", "col")

    def __init__(self, kind, text, line, col):
        self.kind = kind  # "number", "name", "string", "directive", "punct" or "end"
        self.text = text
        self.line = line
        self.col = col

    def __repr__(self):
        return "%s %r at %d:%d" % (self.kind, self.text, self.line, self.col)


_NUMBER = re.compile(r"(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_PUNCT = "{}<>,;()+-*/=.[]:?!&|"


def tokenize(text):
    tokens = []
    i, line, line_start = 0, 1, 0
    n = len(text)

    def here(at):
        return line, at - line_start + 1

    while i < n:
        c = text[i]
        if c == "\n":
            i += 1
            line += 1
            line_start = i
        elif c in " \t\r\f\v":
            i += 1
        elif text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            start = here(i)
            depth, i = 1, i + 2
            while depth and i < n:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    if text[i] == "\n":
                        line, line_start = line + 1, i + 1
                    i += 1
            if depth:
                raise PovError(*start, "a /* comment is never closed")
        elif c == '"':
            start = here(i)
            j = i + 1
            while j < n and text[j] != '"' and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            if j >= n or text[j] != '"':
                raise PovError(*start, "a string is not closed on its line")
            tokens.append(Token("string", text[i + 1:j], *start))
            i = j + 1
        elif c == "#":
            start = here(i)
            m = _NAME.match(text, i + 1)
            if not m:
                raise PovError(*start, "'#' must start a directive such as #declare")
            tokens.append(Token("directive", m.group(0), *start))
            i = m.end()
        elif c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
            m = _NUMBER.match(text, i)
            tokens.append(Token("number", m.group(0), *here(i)))
            i = m.end()
        elif c.isalpha() or c == "_":
            m = _NAME.match(text, i)
            tokens.append(Token("name", m.group(0), *here(i)))
            i = m.end()
        elif c in _PUNCT:
            tokens.append(Token("punct", c, *here(i)))
            i += 1
        else:
            raise PovError(*here(i), "unexpected character %r" % c)
    tokens.append(Token("end", "", *here(i)))
    return tokens


class Stream:
    """The tokens with one-token lookahead and located errors."""

    def __init__(self, tokens):
        self.tokens = tokens
        self.pos = 0

    def peek(self, ahead=0):
        return self.tokens[min(self.pos + ahead, len(self.tokens) - 1)]

    def next(self):
        tok = self.peek()
        if tok.kind != "end":
            self.pos += 1
        return tok

    def at(self, text, kind=None):
        tok = self.peek()
        return tok.text == text and (kind is None or tok.kind == kind)

    def accept(self, text):
        if self.at(text) and self.peek().kind != "string":
            return self.next()
        return None

    def closes(self, what):
        """True past the '}' that ends block `what`; refuses the end of the file inside it."""
        if self.accept("}"):
            return True
        if self.peek().kind == "end":
            raise self.error(self.peek(), "the file ends inside %s { }" % what)
        return False

    def expect(self, text, what=None):
        tok = self.peek()
        if tok.text != text or tok.kind == "string":
            raise self.error(tok, "expected '%s'%s, found %s" % (
                text, " " + what if what else "", describe(tok)))
        return self.next()

    @staticmethod
    def error(tok, message):
        return PovError(tok.line, tok.col, message)


def describe(tok):
    if tok.kind == "end":
        return "the end of the file"
    if tok.kind == "string":
        return 'the string "%s"' % tok.text
    if tok.kind == "directive":
        return "'#%s'" % tok.text
    return "'%s'" % tok.text
