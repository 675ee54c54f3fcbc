#!/usr/bin/env python3
"""The README and docs/ stay readable as they move: every relative link in README.md and
docs/*.md points to an existing file, and every #anchor to a heading there (GitHub's slugs);
the README stays short (a newcomer reads it in five minutes). The checker first proves on a
page of its own that it finds a broken link and a broken anchor."""
import glob, os, re, sys, tempfile

def strip_code(text):
    out, fence = [], False
    for line in text.split('\n'):
        if line.lstrip().startswith('```'):
            fence = not fence; out.append(''); continue
        out.append('' if fence else re.sub(r'`[^`]*`', '', line))
    return '\n'.join(out)

def slug(h):
    h = h.strip().lower()
    h = re.sub(r'[^\w\- ]', '', h)  # GitHub drops punctuation but keeps word chars, '-' and spaces
    return h.replace(' ', '-')

def anchors(path):
    seen, result = {}, set()
    fence = False
    for line in open(path, encoding='utf-8'):
        if line.lstrip().startswith('```'): fence = not fence; continue
        m = not fence and re.match(r'^(#{1,6})\s+(.*?)\s*#*\s*$', line)
        if m:
            s = slug(m.group(2)); n = seen.get(s, 0); seen[s] = n + 1
            result.add(s if n == 0 else f'{s}-{n}')
    return result


def bad_links(md):
    bad = []
    text = strip_code(open(md, encoding='utf-8').read())
    for target in re.findall(r'!?\[[^\]]*\]\(([^)\s]+)(?:\s+"[^"]*")?\)', text):
        if re.match(r'^[a-z]+:', target):
            continue
        path, _, anchor = target.partition('#')
        full = os.path.normpath(os.path.join(os.path.dirname(md), path)) if path else md
        if not os.path.exists(full):
            bad.append(f'{md}: {target}: no such file {full}')
        elif anchor and full.endswith('.md') and anchor not in anchors(full):
            bad.append(f'{md}: {target}: no heading #{anchor} in {full}')
    return bad


def main():
    root = os.path.normpath(os.path.join(os.path.dirname(__file__), '..', '..'))
    with tempfile.TemporaryDirectory() as tmp:
        page = os.path.join(tmp, 'page.md')
        with open(page, 'w', encoding='utf-8') as f:
            f.write('# Here\n[ok](#here) [gone](missing.md) [nowhere](#there) `[code](x.md)`\n')
        found = bad_links(page)
        assert len(found) == 2, f'the checker missed a broken link: {found}'
    pages = [os.path.join(root, 'README.md')] + sorted(glob.glob(os.path.join(root, 'docs', '*.md')))
    bad = [b for md in pages for b in bad_links(md)]
    for b in bad:
        print(b)
    readme_kb = os.path.getsize(os.path.join(root, 'README.md')) / 1024
    print(f'{len(pages)} pages checked, {len(bad)} bad links; README {readme_kb:.1f} kB')
    if readme_kb > 12:
        print('README.md is over 12 kB: move detail to docs/ and link it')
        return 1
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
