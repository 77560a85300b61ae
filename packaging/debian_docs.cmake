# Configure-time step of packaging/CMakeLists.txt: the Debian copyright
# file (machine-readable format, the licence from LICENSE) and the native
# package's changelog, both into DEBIAN_DOCS_DIR.
#   in: PROJECT_SOURCE_DIR, PROJECT_VERSION, DEBIAN_DOCS_DIR, VCPOST_MAINTAINER

# The SPDX name of the licence in LICENSE, from its first lines.
function(vcpost_license_name text out)
  set(name "")
  foreach(pair "MIT License=MIT" "Apache License=Apache-2.0" "Mozilla Public License=MPL-2.0"
               "BSD 3-Clause=BSD-3-clause" "BSD 2-Clause=BSD-2-clause" "ISC License=ISC"
               "Boost Software License=BSL-1.0")
    string(REPLACE "=" ";" pair "${pair}")
    list(GET pair 0 title)
    list(GET pair 1 spdx)
    if(text MATCHES "${title}")
      set(name ${spdx})
      break()
    endif()
  endforeach()
  if(NOT name AND text MATCHES "GNU LESSER GENERAL PUBLIC LICENSE")
    if(text MATCHES "Version 3")
      set(name LGPL-3)
    else()
      set(name LGPL-2.1)
    endif()
  elseif(NOT name AND text MATCHES "GNU GENERAL PUBLIC LICENSE")
    if(text MATCHES "Version 3")
      set(name GPL-3)
    else()
      set(name GPL-2)
    endif()
  endif()
  set(${out} "${name}" PARENT_SCOPE)
endfunction()

string(TIMESTAMP year "%Y" UTC)
set(license_file ${PROJECT_SOURCE_DIR}/LICENSE)
if(EXISTS ${license_file})
  file(READ ${license_file} license_text)
  string(SUBSTRING "${license_text}" 0 400 head)
  vcpost_license_name("${head}" license_name)
  if(NOT license_name)
    set(license_name "custom")
  endif()
  # copyright-format 1.0: the text indented by one space, blank lines as " ."
  string(REGEX REPLACE "\n+$" "" license_text "${license_text}")
  string(REPLACE "\n" "\n " license_body " ${license_text}")
  string(REGEX REPLACE "\n [ \t]*\n" "\n .\n" license_body "${license_body}")
  string(REGEX REPLACE "\n [ \t]*\n" "\n .\n" license_body "${license_body}")
else()
  message(STATUS "LICENSE missing: the package's copyright file names no licence")
  set(license_name "unknown")
  set(license_body " The sources carry no LICENSE file yet.")
endif()
file(WRITE ${DEBIAN_DOCS_DIR}/copyright
"Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/
Upstream-Name: vcpost
Upstream-Contact: ${VCPOST_MAINTAINER}

Files: *
Copyright: ${year} The vcpost authors
License: ${license_name}

License: ${license_name}
${license_body}
")

# A native package's changelog (Debian's format, compressed when installed).
string(TIMESTAMP date "%a, %d %b %Y %H:%M:%S +0000" UTC)
file(WRITE ${DEBIAN_DOCS_DIR}/changelog
"vcpost (${PROJECT_VERSION}) unstable; urgency=medium

  * vcpost ${PROJECT_VERSION}, packaged with CPack from the project's sources.

 -- ${VCPOST_MAINTAINER}  ${date}
")
