#!/usr/bin/env bash
# Issues an identity for NODE, signed by the identity CA of PKI_DIR (scripts/make_pki.sh), that
# expired in 2020: OUT_DIR/identity.pem and OUT_DIR/key.pem. A test aid: `openssl x509` cannot
# backdate, `openssl ca` can.
# usage: make_expired_identity.sh PKI_DIR NODE OUT_DIR
set -euo pipefail
pki=$1
node=$2
out=$3
db=$out/ca-db
mkdir -p "$db"
: >"$db/index.txt"
echo 01 >"$db/serial"
cat >"$db/ca.cnf" <<CNF
[ca]
default_ca = expired
[expired]
database = $db/index.txt
new_certs_dir = $db
serial = $db/serial
default_md = sha256
policy = any
[any]
organizationName = optional
commonName = supplied
CNF
openssl genpkey -algorithm EC -pkeyopt ec_paramgen_curve:prime256v1 -out "$out/key.pem" 2>/dev/null
openssl req -new -key "$out/key.pem" -subj "/O=teleop/CN=$node" -out "$db/request.csr"
openssl ca -batch -notext -preserveDN -config "$db/ca.cnf" -cert "$pki/identity_ca.pem" \
  -keyfile "$pki/ca/identity_ca_key.pem" -startdate 20200101000000Z -enddate 20200102000000Z \
  -in "$db/request.csr" -out "$out/identity.pem" 2>/dev/null
