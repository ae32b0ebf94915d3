#!/usr/bin/env python3
# Counts the public API from rustdoc HTML: top-level items (types, traits, functions, constants) and their
# members (inherent methods and associated constants, trait items, enum variants, struct fields).
# Usage: cargo doc --no-deps --all-features && python3 tools/public-api.py target/doc/quatprop
import re,sys,os,glob
d=sys.argv[1]
items=[];members=0;names={}
for f in sorted(glob.glob(d+'/**/*.html',recursive=True)):
    b=os.path.basename(f); t=open(f).read()
    if 'http-equiv="refresh"' in t: continue
    m=re.match(r'(struct|enum|trait|fn|constant|type|macro|static|union)\.(.*)\.html',b)
    if not m: continue
    items.append(os.path.relpath(f,d)); names.setdefault(m.group(2),[]).append(os.path.relpath(f,d))
    if m.group(1)=='trait':
        # trait's own required/provided items
        sec=t.split('id="implementors"')[0]
        members+=len(set(re.findall(r'id="((?:tymethod|method|associatedconstant|associatedtype)\.[^"]+)"',sec)))
    elif m.group(1) in('struct','enum'):
        # inherent impls only
        s=t.find('id="implementations-list"'); e=t.find('id="trait-implementations"')
        sec=t[s:e] if s>=0 else ''
        members+=len(set(re.findall(r'id="((?:method|associatedconstant)\.[^"]+)"',sec)))
        members+=len(set(re.findall(r'id="(variant\.[^"]+|structfield\.[^"]+)"',t)))
print("items",len(items),"members",members,"total",len(items)+members)
print("dup names",{k:v for k,v in names.items() if len(v)>1})
